#include "view/window/x11_errors.h"

#include <cstdio>

#include <X11/Xlib.h>

namespace tessera::view::x11 {
namespace {

// Set from Xlib's callbacks, read by the frame loop on the same thread.
bool g_gone = false;
char g_first[160] = "";
std::jmp_buf* g_lost_display = nullptr;
bool g_saved = false;
XErrorHandler g_previous = nullptr;
XIOErrorHandler g_previous_io = nullptr;

// A protocol error: recorded, never fatal here. The handler may not send requests, and
// XGetErrorText only reads Xlib's error database.
int on_error(Display* display, XErrorEvent* e) {
    if (!g_gone) {
        char text[96] = "";
        XGetErrorText(display, e->error_code, text, sizeof text);
        std::snprintf(g_first, sizeof g_first, "%s, request %d", text, int(e->request_code));
    }
    g_gone = true;
    return 0;
}

// The connection is gone: Xlib exits if this returns, so it jumps back to the frame loop,
// which touches X no more. Without a jump target, Xlib's own handler (message, exit 1).
int on_io_error(Display* display) {
    if (g_lost_display) std::longjmp(*g_lost_display, 1);
    return g_previous_io ? g_previous_io(display) : 0;
}

}  // namespace

void watch_errors(std::jmp_buf* lost_display) {
    g_lost_display = lost_display;
    XErrorHandler was = XSetErrorHandler(on_error);
    XIOErrorHandler was_io = XSetIOErrorHandler(on_io_error);
    if (!g_saved) g_previous = was, g_previous_io = was_io, g_saved = true;
}

void unwatch_errors() {
    if (!g_saved) return;
    XSetErrorHandler(g_previous);
    XSetIOErrorHandler(g_previous_io);
    g_lost_display = nullptr;
    g_saved = false;
}

bool window_gone() { return g_gone; }

const char* first_error() { return g_first; }

}  // namespace tessera::view::x11
