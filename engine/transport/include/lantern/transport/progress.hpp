// A one-line progress bar on stderr for long computations (the transport reference,
// lantern-bench accuracy).
//
// On a terminal the line is redrawn in place ("\r"), at most ten times a second. Elsewhere
// (CI logs, pipes) nothing is drawn while running and finish() prints one summary line, so
// logs stay short.
//
// Threads: one thread at a time (the computation's main thread).
#pragma once

#include <cstdint>
#include <string>

namespace lantern::transport {

class ProgressBar {
  public:
    explicit ProgressBar(std::string label);
    ~ProgressBar(); // ends a drawn line that finish() did not
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    // fraction in [0, 1] (clamped), status: a short text after the bar.
    void update(double fraction, const std::string& status);
    // Prints the final state on its own line.
    void finish(const std::string& status);

  private:
    void draw(double fraction, const std::string& status);

    std::string label_;
    bool interactive_ = false; // stderr is a terminal
    bool drawn_ = false;       // a line is open on the terminal
    std::int64_t last_draw_ns_ = 0;
};

} // namespace lantern::transport
