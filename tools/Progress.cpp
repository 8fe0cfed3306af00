#include "Progress.h"

#include "image/InputError.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gpurt {

namespace {
constexpr int kSteps = 20;             // Lines: one line per 1/20 = 5%
constexpr double kBarInterval = 0.1;   // Bar: redrawn at most ten times a second
constexpr int kBarWidth = 30;

double secondsBetween(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}
}  // namespace

ProgressDisplay::ProgressDisplay(Mode mode, double units, std::string unitName)
    : mode_(mode), units_(units), unitName_(std::move(unitName)), start_(std::chrono::steady_clock::now()),
      lastDraw_(start_) {}

ProgressDisplay::~ProgressDisplay() {
    // An error ended the work: the bar's line is ended so that the error has a line of its own.
    if (mode_ == Mode::Bar && !finished_ && fraction_ > 0.0) std::fputc('\n', stderr);
}

double ProgressDisplay::secondsLeft() const {
    if (fraction_ <= 0.0) return 0.0;
    const double elapsed = secondsBetween(start_, std::chrono::steady_clock::now());
    return elapsed * (1.0 - fraction_) / fraction_;
}

void ProgressDisplay::update(double fraction) {
    if (mode_ == Mode::Off || finished_ || !(fraction > fraction_)) return;
    fraction_ = std::min(1.0, fraction);
    if (mode_ == Mode::Bar) {
        drawBar(false);
        return;
    }
    const int step = int(std::floor(fraction_ * kSteps + 1e-9));
    if (step > lastStep_ && fraction_ < 1.0) {
        lastStep_ = step;
        printLine();
    }
}

void ProgressDisplay::mark() {
    if (mode_ == Mode::Lines && !finished_ && fraction_ < 1.0) printLine();
}

void ProgressDisplay::finish() {
    if (mode_ == Mode::Off || finished_) return;
    fraction_ = 1.0;
    if (mode_ == Mode::Lines) {
        printLine();
    } else {
        drawBar(true);
        std::fputc('\n', stderr);
    }
    finished_ = true;
}

void ProgressDisplay::printLine() {
    // Two decimals, as scripts read it; the same fraction twice (a frame's end on a 5% step) once.
    // 1.00 only once done.
    const double shown = std::min(std::round(fraction_ * 100.0) / 100.0, fraction_ < 1.0 ? 0.99 : 1.0);
    if (shown <= lastPrinted_) return;
    lastPrinted_ = shown;
    if (active_)
        std::fprintf(stderr, "progress %.2f eta %.1fs active %llu\n", shown, secondsLeft(), (unsigned long long)*active_);
    else
        std::fprintf(stderr, "progress %.2f eta %.1fs\n", shown, secondsLeft());
    std::fflush(stderr);
}

void ProgressDisplay::drawBar(bool force) {
    const auto now = std::chrono::steady_clock::now();
    if (!force && secondsBetween(lastDraw_, now) < kBarInterval) return;
    lastDraw_ = now;
    const int filled = int(fraction_ * kBarWidth);
    std::string bar(size_t(filled), '=');
    if (filled < kBarWidth) bar += '>';
    bar.resize(size_t(kBarWidth), ' ');
    const double elapsed = secondsBetween(start_, now);
    char rate[64] = "";
    if (units_ > 0.0 && elapsed > 0.0)
        std::snprintf(rate, sizeof rate, "  %.3g %s/s", units_ * fraction_ / elapsed, unitName_.c_str());
    const double left = secondsLeft();
    char time[48];
    if (fraction_ >= 1.0)
        std::snprintf(time, sizeof time, "%.1f s", elapsed);
    else
        std::snprintf(time, sizeof time, "%dm%02ds left", int(left) / 60, int(left) % 60);
    // \r and clear to the end of the line: the bar redraws itself in place.
    char active[48] = "";
    if (active_) std::snprintf(active, sizeof active, "  %llu px active", (unsigned long long)*active_);
    std::fprintf(stderr, "\r[%s] %3d%%%s%s  %s\033[K", bar.c_str(), int(fraction_ * 100.0), rate, active, time);
    std::fflush(stderr);
}

void ProgressCliOptions::add(CLI::App& cmd) {
    cmd.add_flag("--progress", progress,
                 "Print the progress on stderr as plain lines 'progress 0.35 eta 12.1s' (one per 5% and per "
                 "frame, the last at 1.00); without it a terminal shows a bar and anything else nothing");
    cmd.add_flag("--quiet", quiet, "No progress bar, and a warning said once however often it recurs");
}

ProgressDisplay::Mode ProgressCliOptions::mode() const {
    setWarningRepeats(!quiet);
    if (progress) return ProgressDisplay::Mode::Lines;
    if (!quiet && isatty(STDERR_FILENO)) return ProgressDisplay::Mode::Bar;
    return ProgressDisplay::Mode::Off;
}

}  // namespace gpurt
