// The message of the exception a call throws, for tests that check what an error says.
#pragma once
#include <exception>
#include <string>

#include <gtest/gtest.h>

namespace tessera::test {

/// e.what() of the std::exception f() throws; when it throws none, a test failure and
/// "<no exception>" (which no expected message contains).
template <class F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    ADD_FAILURE() << "no exception";
    return "<no exception>";
}

}  // namespace tessera::test
