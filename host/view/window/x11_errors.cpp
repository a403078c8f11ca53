#include "view/window/x11_errors.h"

#include <cstdio>
#include <cstring>

#include <X11/Xlib.h>

// GLFW's X11 accessors (glfw3native.h declares them, but with GLFW_EXPOSE_NATIVE_X11 it
// also includes Xrandr's header, a package the viewer needs nothing else from).
extern "C" Display* glfwGetX11Display(void);
extern "C" Window glfwGetX11Window(GLFWwindow* window);

namespace tessera::view::x11 {
namespace {

// Set from Xlib's callbacks, read by the frame loop on the same thread.
bool g_pending = false, g_gone = false;
int g_ignored = 0;
char g_last[192] = "", g_gone_error[192] = "";
std::jmp_buf* g_lost_display = nullptr;
bool g_saved = false;
XErrorHandler g_previous = nullptr;
XIOErrorHandler g_previous_io = nullptr;

// A protocol error: recorded for the frame loop, never fatal here. The handler may not
// send requests; XGetErrorText and XGetErrorDatabaseText only read Xlib's database (an
// extension's request has no name there and keeps its number).
int on_error(Display* display, XErrorEvent* e) {
    if (!g_pending) {
        char text[96] = "", number[16] = "", request[64] = "";
        XGetErrorText(display, e->error_code, text, sizeof text);
        std::snprintf(number, sizeof number, "%d", int(e->request_code));
        XGetErrorDatabaseText(display, "XRequest", number, number, request, sizeof request);
        std::snprintf(g_last, sizeof g_last, "%s, request %s", text, request);
    }
    g_pending = true;
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

bool window_gone(GLFWwindow* window) {
    if (g_gone || !g_pending) return g_gone;
    char error[sizeof g_last];
    std::memcpy(error, g_last, sizeof error);
    g_pending = false;
    XWindowAttributes attributes;  // a round trip: its own error, if any, arrives before it returns
    if (XGetWindowAttributes(glfwGetX11Display(), glfwGetX11Window(window), &attributes) != 0 && !g_pending) {
        if (g_ignored < 3) std::fprintf(stderr, "tessera view: X error ignored (the window is still there): %s\n", error);
        ++g_ignored;
        return false;
    }
    std::memcpy(g_gone_error, error, sizeof error);
    g_gone = true;
    return true;
}

const char* gone_error() { return g_gone_error; }

}  // namespace tessera::view::x11
