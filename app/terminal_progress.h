#pragma once
// A one-line progress display on stderr for long stages: redrawn in place on a terminal, one line per stage
// otherwise (logs stay readable).
#include <unistd.h>

#include <cstdio>
#include <string>

#include "core/util/progress.h"

namespace facehex::cli {

class TerminalProgress {
 public:
  TerminalProgress() : tty_(isatty(fileno(stderr)) != 0) {}
  ~TerminalProgress() { finish(); }

  ProgressCallback callback() {
    return [this](const std::string& stage, double fraction) {
      const int percent = static_cast<int>(100 * fraction);
      if (tty_) {
        std::fprintf(stderr, "\r  %-40s %3d%%", stage.c_str(), percent);
        dirty_ = true;
      } else if (stage != last_stage_) {
        std::fprintf(stderr, "  %s\n", stage.c_str());
      }
      last_stage_ = stage;
      return true;
    };
  }

  void finish() {
    if (tty_ && dirty_) std::fprintf(stderr, "\r%60s\r", "");
    dirty_ = false;
  }

 private:
  bool tty_;
  bool dirty_ = false;
  std::string last_stage_;
};

}  // namespace facehex::cli
