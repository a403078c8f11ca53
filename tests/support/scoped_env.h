// Sets (or, with value nullptr, unsets) an environment variable for one scope and
// restores its previous value (or its absence) after. Used for TESSERA_CL_OPTIONS, on which the program cache keys, so that
// kernels are really rebuilt with the options a test gives.
#pragma once
#include <cstdlib>
#include <string>

namespace tessera::test {

class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old, had_ = true;
        if (value) setenv(name, value, 1);
        else unsetenv(name);
    }
    ~ScopedEnv() {
        if (had_) setenv(name_.c_str(), old_.c_str(), 1);
        else unsetenv(name_.c_str());
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    std::string name_, old_;
    bool had_ = false;
};

}  // namespace tessera::test
