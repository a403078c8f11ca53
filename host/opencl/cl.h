// The OpenCL C++ bindings, configured once for the whole project (OpenCL 1.2, with
// exceptions so every failing call surfaces as cl::Error).
#pragma once
#ifndef CL_HPP_ENABLE_EXCEPTIONS
#define CL_HPP_ENABLE_EXCEPTIONS
#endif
#include <CL/opencl.hpp>

#include <string>

namespace tessera {
/// "clBuildProgram: CL_BUILD_PROGRAM_FAILURE (-11)" style text for a cl::Error.
std::string describe_cl_error(const cl::Error& e);
}  // namespace tessera
