// check-layers fixture: the other half of a folder cycle.
#pragma once
#include "gi/a.h"
