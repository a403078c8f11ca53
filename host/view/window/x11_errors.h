// The window's X errors (x11_errors.cpp): Xlib's default handlers print and call exit(1),
// so a window destroyed from outside (`xdotool windowclose`, another client) or a lost
// connection (the X server ended, or a client killed this one: `xdotool windowkill`)
// ended `tessera view` with no closing line and no --times. These handlers turn the
// first into "the window is gone" and the second into a jump back to the frame loop, so
// the viewer ends its run and writes what it owes.
#pragma once
#include <csetjmp>

struct GLFWwindow;

namespace tessera::view::x11 {

/// Installs the handlers. GLFW 3.3 puts Xlib's default protocol-error handler back after
/// each of its own guarded calls (window and context creation), so the frame loop calls
/// this each frame: it is a pointer swap. An I/O error (the connection lost) longjmps to
/// `lost_display` with 1 when it is non-null; Xlib's own handler (exit 1) otherwise.
/// After the jump no X call may be made: Xlib may still hold the display's lock.
void watch_errors(std::jmp_buf* lost_display);

/// Puts back the handlers that were there before the first watch_errors.
void unwatch_errors();

/// Whether `window` is gone: after an X protocol error the server is asked whether it
/// still knows the window (a destroyed window answers BadWindow or BadDrawable, by the
/// request that first meets it). An error that leaves the window is said on stderr (the
/// first three) and the run goes on. Once gone, stays gone.
bool window_gone(GLFWwindow* window);

/// The error that took the window ("BadWindow (invalid Window parameter), request
/// X_GetWindowAttributes"), for the message.
const char* gone_error();

}  // namespace tessera::view::x11
