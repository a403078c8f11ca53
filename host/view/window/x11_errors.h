// The window's X errors (x11_errors.cpp): Xlib's default handlers print and call exit(1),
// so a window destroyed from outside (`xdotool windowclose`, a window manager's kill) or
// a lost X server ended `tessera view` with no closing line and no --times. These
// handlers turn the first into "the window is gone" and the second into a jump back to
// the frame loop, so the viewer ends its run and writes what it owes.
#pragma once
#include <csetjmp>

namespace tessera::view::x11 {

/// Installs the handlers (again: GLFW 3.3 resets the protocol-error handler to Xlib's
/// default after each of its own guarded calls, so the frame loop calls this every
/// frame). A protocol error on the window (BadWindow, BadDrawable, GLXBadDrawable, ...)
/// sets window_gone(); an I/O error (the connection lost) longjmps to `lost_display`
/// with 1 when it is non-null, and exits with status 1 as Xlib's own handler otherwise.
void watch_errors(std::jmp_buf* lost_display);

/// Puts back the handlers that were there before the first watch_errors.
void unwatch_errors();

/// An X protocol error has arrived since watch_errors: the window cannot be drawn to.
bool window_gone();

/// The first such error's name ("BadWindow (request X_GetGeometry)"), for the message.
const char* first_error();

}  // namespace tessera::view::x11
