// The progress of a long command on stderr (render's samples, rows and frames; pack's steps), as
// pbrt-v4 and Blender show it: on a terminal a one-line bar with the rate and the time left,
// redrawn in place; with --progress plain lines for scripts and farm logs,
//     progress 0.35 eta 12.1s
// (the fraction done, rising, with two decimals, and the estimated seconds left), one each time
// the fraction passes a multiple of 5%, one at the end of each frame, and one at 1.00 at the end;
// otherwise nothing. Kept to this one file pair: Debian's progress-bar libraries (indicators,
// libprogressbar) would add a dependency for forty lines.
#pragma once

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace gpurt {

class ProgressDisplay {
  public:
    enum class Mode { Off, Lines, Bar };

    // `units` and `unitName`: what the bar counts for its rate ("samples", 0: no rate).
    ProgressDisplay(Mode mode, double units = 0.0, std::string unitName = {});
    ~ProgressDisplay();
    ProgressDisplay(const ProgressDisplay&) = delete;
    ProgressDisplay& operator=(const ProgressDisplay&) = delete;

    // The fraction done so far; a fraction below the last one is ignored (shown rising).
    void update(double fraction);
    // The end of a unit of work (a frame): a line now in Lines mode.
    void mark();
    // Done: the fraction 1 (the bar's line ended).
    void finish();
    // Adaptive sampling: the pixels still active, shown after the fraction from now on
    // ("progress 0.35 eta 12.1s active 1234"; the bar: "1234 px active").
    void setActive(uint64_t active) { active_ = active; }

    Mode mode() const { return mode_; }

  private:
    void printLine();
    void drawBar(bool force);
    double secondsLeft() const;

    Mode mode_;
    double units_;
    std::string unitName_;
    double fraction_ = 0.0;
    int lastStep_ = 0;                // Lines: the last multiple of 5% printed
    double lastPrinted_ = -1.0;       // Lines: the last fraction printed
    bool finished_ = false;
    std::optional<uint64_t> active_;
    std::chrono::steady_clock::time_point start_, lastDraw_;
};

// --progress and --quiet of the commands that show progress (render, pack, view).
struct ProgressCliOptions {
    bool progress = false, quiet = false;

    void add(CLI::App& cmd);
    // Lines with --progress; else a bar when stderr is a terminal and --quiet is not given; else
    // Off. Also applies --quiet to the warnings (image/InputError.h setWarningRepeats).
    ProgressDisplay::Mode mode() const;
};

}  // namespace gpurt
