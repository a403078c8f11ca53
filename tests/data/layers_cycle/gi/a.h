// check-layers fixture: one half of a folder cycle.
#pragma once
#include "integrators/b.h"
