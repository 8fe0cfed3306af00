#include "stream/GLWindow.h"

#include "stream/GL.h"
#include "stream/StreamErrors.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <string>

namespace gpurt {

namespace {
std::string glfwErrorText;
void recordError(int, const char* description) { glfwErrorText = description ? description : "unknown error"; }

GLWindow* owner(GLFWwindow* w) { return static_cast<GLWindow*>(glfwGetWindowUserPointer(w)); }
}  // namespace

GLWindow::GLWindow(int width, int height, const std::string& title) {
    glfwSetErrorCallback(recordError);
    if (!glfwInit())
        throw EnvironmentError("no display to open a window on (" + glfwErrorText + ")");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_FALSE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw EnvironmentError("no OpenGL 4.5 core window context (" + glfwErrorText + ")");
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(0);  // a progressive renderer draws as fast as it can
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress))) {
        glfwDestroyWindow(window_);
        glfwTerminate();
        throw EnvironmentError("loading OpenGL 4.5 functions for the window failed");
    }
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, keyCallback);
    glfwSetMouseButtonCallback(window_, buttonCallback);
    glfwSetCursorPosCallback(window_, cursorCallback);
    glfwSetScrollCallback(window_, scrollCallback);
    glfwSetFramebufferSizeCallback(window_, sizeCallback);
}

GLWindow::~GLWindow() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

void GLWindow::pollEvents() {
    events_.clear();
    glfwPollEvents();
}

bool GLWindow::closeRequested() const { return glfwWindowShouldClose(window_); }
void GLWindow::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void GLWindow::swapBuffers() { glfwSwapBuffers(window_); }
void GLWindow::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

int GLWindow::width() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return w;
}

int GLWindow::height() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return h;
}

std::vector<unsigned char> GLWindow::readPixels() const {
    const int w = width(), h = height();
    std::vector<unsigned char> bottomFirst(size_t(w) * size_t(h) * 3), topFirst(bottomFirst.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, bottomFirst.data());
    const size_t row = size_t(w) * 3;
    for (int y = 0; y < h; ++y)
        std::copy_n(bottomFirst.data() + size_t(h - 1 - y) * row, row, topFirst.data() + size_t(y) * row);
    return topFirst;
}

void GLWindow::keyCallback(GLFWwindow* w, int key, int, int action, int) {
    if (action == GLFW_PRESS || action == GLFW_REPEAT || action == GLFW_RELEASE)
        owner(w)->events_.push_back({WindowEvent::Key, key, action != GLFW_RELEASE, 0, 0});
}

void GLWindow::buttonCallback(GLFWwindow* w, int button, int action, int) {
    owner(w)->events_.push_back({WindowEvent::MouseButton, button, action == GLFW_PRESS, 0, 0});
}

void GLWindow::cursorCallback(GLFWwindow* w, double x, double y) {
    owner(w)->events_.push_back({WindowEvent::CursorMove, 0, false, x, y});
}

void GLWindow::scrollCallback(GLFWwindow* w, double x, double y) {
    owner(w)->events_.push_back({WindowEvent::Scroll, 0, false, x, y});
}

void GLWindow::sizeCallback(GLFWwindow* w, int width, int height) {
    owner(w)->events_.push_back({WindowEvent::Resize, 0, false, double(width), double(height)});
}

}  // namespace gpurt
