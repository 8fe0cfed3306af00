// A window with an OpenGL 4.5 core context (GLFW 3: GLX under X11), current on the calling thread
// for its lifetime: the stream context of an interactive program, whose kernels render into
// streams as headless ones do, with a present pass drawing into its default framebuffer. Input
// arrives as events, read after pollEvents().
#pragma once

#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace gpurt {

struct WindowEvent {
    enum Type { Key, MouseButton, CursorMove, Scroll, Resize } type;
    int key = 0;        // GLFW key code (Key), button (MouseButton)
    bool press = false; // key or button pressed (true) or released
    double x = 0, y = 0;  // cursor position (CursorMove), scroll offsets (Scroll), size (Resize)
};

class GLWindow {
  public:
    // Opens the window (framebuffer width x height) and makes its context current; throws
    // EnvironmentError with one line when there is no display or no 4.5 core context.
    GLWindow(int width, int height, const std::string& title);
    ~GLWindow();
    GLWindow(const GLWindow&) = delete;
    GLWindow& operator=(const GLWindow&) = delete;

    // Processes the window system's events into events(), which it clears first.
    void pollEvents();
    const std::vector<WindowEvent>& events() const { return events_; }
    bool closeRequested() const;
    void requestClose();
    void swapBuffers();
    void setTitle(const std::string& title);
    // The size of the default framebuffer in pixels.
    int width() const;
    int height() const;
    // The back buffer's pixels as 8-bit RGB, top row first (waits for the GL).
    std::vector<unsigned char> readPixels() const;

  private:
    GLFWwindow* window_ = nullptr;
    std::vector<WindowEvent> events_;
    static void keyCallback(GLFWwindow*, int key, int, int action, int);
    static void buttonCallback(GLFWwindow*, int button, int action, int);
    static void cursorCallback(GLFWwindow*, double x, double y);
    static void scrollCallback(GLFWwindow*, double x, double y);
    static void sizeCallback(GLFWwindow*, int width, int height);
};

}  // namespace gpurt
