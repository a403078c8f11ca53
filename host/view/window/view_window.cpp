// The viewer's window (libtessera_view_window.so, loaded by `tessera view`): GLFW with an
// OpenGL context (Mesa's software renderer suffices), the image as a texture drawn behind
// a Dear ImGui heads-up display. Everything else — camera, passes, HUD text — is the
// host's (view/window_api.h): this file only moves pixels and events.
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "view/window/x11_errors.h"
#include "view/window_api.h"

using tessera::view::InputEvent;
using tessera::view::WindowHost;
namespace x11 = tessera::view::x11;

namespace {

struct WindowState {
    WindowHost* host = nullptr;
    bool dragging = false;
    double last_x = 0, last_y = 0;
    std::string glfw_error;
};

WindowState* state_of(GLFWwindow* w) { return static_cast<WindowState*>(glfwGetWindowUserPointer(w)); }

void on_glfw_error(int, const char* description) {
    std::fprintf(stderr, "tessera view: GLFW: %s\n", description);
}

// GLFW's codes of printable keys are their upper-case ASCII codes, and GLFW_KEY_ESCAPE is
// 256 like kKeyEscape; other keys (arrows, function keys) are not bound. A press with
// Ctrl, Alt or Super is the desktop's or a terminal's shortcut, not ours (Alt+M switched
// the method); releases always pass, so a held key never sticks.
void on_key(GLFWwindow* w, int key, int, int action, int mods) {
    if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
    if (action == GLFW_REPEAT || !(key == GLFW_KEY_ESCAPE || (key >= 32 && key < 128))) return;
    if (action == GLFW_PRESS && (mods & (GLFW_MOD_CONTROL | GLFW_MOD_ALT | GLFW_MOD_SUPER))) return;
    const InputEvent::Kind kind = action == GLFW_PRESS ? InputEvent::Kind::Press : InputEvent::Kind::Release;
    state_of(w)->host->input({kind, key});
}

void on_mouse_button(GLFWwindow* w, int button, int action, int) {
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    WindowState* s = state_of(w);
    s->dragging = action == GLFW_PRESS && !(ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse);
    glfwGetCursorPos(w, &s->last_x, &s->last_y);
}

void on_cursor(GLFWwindow* w, double x, double y) {
    WindowState* s = state_of(w);
    if (s->dragging)
        s->host->input({InputEvent::Kind::Drag, 0, static_cast<float>(x - s->last_x), static_cast<float>(y - s->last_y)});
    s->last_x = x, s->last_y = y;
}

void on_scroll(GLFWwindow* w, double, double dy) {
    state_of(w)->host->input({InputEvent::Kind::Scroll, 0, 0.0f, static_cast<float>(dy)});
}

// Reads the window's w x h pixels into `rgba` (RGBA, row 0 at the top), in place: no
// buffer of the frame loop's own, which an X I/O error's longjmp could leave unfreed.
void read_window(int w, int h, std::vector<uint8_t>& rgba) {
    rgba.resize(size_t(w) * h * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    for (int y = 0; y < h / 2; ++y)  // OpenGL's row 0 is the bottom
        std::swap_ranges(rgba.begin() + size_t(y) * w * 4, rgba.begin() + size_t(y + 1) * w * 4,
                         rgba.begin() + size_t(h - 1 - y) * w * 4);
}

// The rows a HUD line takes in `width` pixels of text: broken between its " | " parts
// (ImGui's own wrap also breaks after a '.', which split numbers: "PM 0." / "0 ms"), a
// part wider than the width alone cut to fit with "...", so that no row wraps.
std::vector<std::string> hud_rows(const std::string& line, float width) {
    std::vector<std::string> rows;
    std::string row;
    for (size_t at = 0; at <= line.size(); at += 3) {
        const size_t bar = std::min(line.find(" | ", at), line.size());
        std::string part = line.substr(at, bar - at);
        while (part.size() > 1 && ImGui::CalcTextSize((part + "...").c_str()).x > width) part.pop_back();
        if (part.size() < bar - at) part += "...";
        const std::string longer = row.empty() ? part : row + " | " + part;
        if (!row.empty() && ImGui::CalcTextSize(longer.c_str()).x > width) {
            rows.push_back(row);
            row = part;
        } else {
            row = longer;
        }
        at = bar;
    }
    rows.push_back(row);
    return rows;
}

void draw_hud(WindowHost& host, double fps) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.6f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
    if (ImGui::Begin("Tessera", nullptr, flags)) {
        // Under 400 pixels wide the HUD's 9-12 lines would cover the image: three quarters
        // of the font's size there.
        if (ImGui::GetIO().DisplaySize.x < 400) ImGui::SetWindowFontScale(0.75f);
        // The text's width: the window less the HUD's place (8), its padding (2 x 8) and a
        // margin (8); the auto-sized HUD grows to its longest row.
        const float width = ImGui::GetIO().DisplaySize.x - 32;
        for (const std::string& line : host.hud(fps))
            for (const std::string& row : hud_rows(line, width)) ImGui::TextUnformatted(row.c_str());
    }
    ImGui::End();
}

// Where the image goes in a window of `display` pixels: as large as fits at its own
// aspect, centred on whole pixels, black bars elsewhere. The window is made at the
// image's size and is not resizable, but a window manager or a client (`xdotool
// windowsize`) can resize it anyway, which stretched the image.
ImVec4 image_rect(ImVec2 display, int w, int h) {
    const float scale = std::min(display.x / float(w), display.y / float(h));
    const float iw = std::round(w * scale), ih = std::round(h * scale);
    const float x = std::floor(0.5f * (display.x - iw)), y = std::floor(0.5f * (display.y - ih));
    return {x, y, x + iw, y + ih};
}

int fail(char* error, size_t size, const std::string& message) {
    std::snprintf(error, size, "%s", message.c_str());
    return 1;
}

// The frame loop: events, the host's frame, the image and the HUD, until the host is
// done, the window is closed, or the window is gone (x11_errors.h). An X I/O error
// longjmps out of it from any call that reaches X (GLFW's, ImGui's GLFW backend's, or
// OpenGL's through Mesa), so no C++ object with a destructor is alive across them here:
// the capture buffer is the caller's.
void frame_loop(GLFWwindow* window, WindowHost* host, GLuint texture, std::jmp_buf* lost_display,
                std::vector<uint8_t>& capture) {
    // The HUD's rate: 1 / an exponential average of the frame interval (weight 0.3 for the
    // newest), from the second frame on (the first interval includes the window's set-up).
    double last = glfwGetTime(), mean_dt = 0.0;
    int frame = 0;
    while (!glfwWindowShouldClose(window) && !host->done()) {
        x11::watch_errors(lost_display);
        if (x11::window_gone(window)) break;
        if (host->idle())
            glfwWaitEventsTimeout(1.0 / 30.0);  // converged or paused: no busy loop
        else
            glfwPollEvents();
        const double now = glfwGetTime(), dt = now - last;
        last = now;
        if (frame == 1) mean_dt = dt;
        else if (frame > 1) mean_dt = 0.7 * mean_dt + 0.3 * dt;
        const double fps = mean_dt > 0 ? 1.0 / mean_dt : 0.0;
        // The window's sizes, before the host's frame: round trips that meet a window
        // destroyed since, which must end the loop before their unfilled sizes are used.
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        int fw = 0, fh = 0;
        glfwGetFramebufferSize(window, &fw, &fh);
        if (x11::window_gone(window)) break;
        host->frame(dt);
        if (host->done()) break;
        const std::vector<uint8_t>& pixels = host->pixels();
        glBindTexture(GL_TEXTURE_2D, texture);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, host->width(), host->height(), GL_RGBA, GL_UNSIGNED_BYTE,
                        pixels.data());

        ImGui::NewFrame();
        const ImVec2 size = ImGui::GetIO().DisplaySize;
        const ImVec4 at = image_rect(size, host->width(), host->height());
        ImGui::GetBackgroundDrawList()->AddImage(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(texture)),
                                                 ImVec2(at.x, at.y), ImVec2(at.z, at.w));
        if (host->hud_visible()) draw_hud(*host, fps);
        ImGui::Render();
        glViewport(0, 0, fw, fh);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (frame == host->capture_frame()) {
            glFinish();
            read_window(fw, fh, capture);
            host->window_captured(capture, fw, fh);
        }
        glfwSwapBuffers(window);
        ++frame;
    }
}

}  // namespace

extern "C" int tessera_view_window_abi() { return tessera::view::kWindowAbiVersion; }

extern "C" int tessera_view_window_probe(char* error, size_t error_size) {
    glfwSetErrorCallback(nullptr);  // the reason goes into the one-line error instead
    if (!glfwInit()) {
        const char* why = nullptr;
        glfwGetError(&why);
        return fail(error, error_size, std::string("no display (GLFW: ") + (why ? why : "cannot initialise") + ")");
    }
    glfwTerminate();
    return 0;
}

extern "C" int tessera_view_window_run(WindowHost* host, char* error, size_t error_size) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit())
        return fail(error, error_size, "no display: GLFW could not initialise (is DISPLAY set?)");
    // OpenGL 3.0 is what ImGui's GL3 renderer needs with GLSL 1.30; Mesa's llvmpipe has it.
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(host->width(), host->height(), host->title().c_str(), nullptr, nullptr);
    if (!window) {
        glfwTerminate();
        return fail(error, error_size, "no OpenGL 3.0 context: GLFW could not create the window");
    }
    WindowState state;
    state.host = host;
    glfwSetWindowUserPointer(window, &state);
    glfwMakeContextCurrent(window);
    glfwSwapInterval(0);  // no vsync: the HUD's rate is the renderer's
    glfwSetKeyCallback(window, on_key);
    glfwSetMouseButtonCallback(window, on_mouse_button);
    glfwSetCursorPosCallback(window, on_cursor);
    glfwSetScrollCallback(window, on_scroll);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);  // chains to the callbacks above
    ImGui_ImplOpenGL3_Init("#version 130");

    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, host->width(), host->height(), 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);

    // A lost X connection jumps back here (x11_errors.h), from the frame loop or the
    // clean-up below: nothing of X or OpenGL is touched after it, not even to clean up,
    // and the program ends its run without the window.
    std::vector<uint8_t> capture;
    std::jmp_buf lost_display;
    if (setjmp(lost_display)) {
        x11::unwatch_errors();
        fail(error, error_size, "lost the connection to the X server (the server ended, or a client killed this one)");
        return tessera::view::kWindowLostDisplay;
    }
    frame_loop(window, host, texture, &lost_display, capture);
    if (x11::window_gone(window)) {
        // Destroyed from outside: its OpenGL context and GLFW's state would raise more X
        // errors on the way down, so they are left to the process's exit.
        x11::unwatch_errors();
        std::fprintf(stderr, "tessera view: the window was destroyed (X error: %s); ending the run as if closed\n",
                     x11::gone_error());
        return 0;
    }
    glDeleteTextures(1, &texture);
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window);
    glfwTerminate();
    x11::unwatch_errors();  // only now: the server may end during the clean-up too
    return 0;
}
