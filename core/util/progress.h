#pragma once
// Progress reporting for long stages. The callback receives a stage name and a fraction in [0, 1] and returns false
// to ask for cancellation; the computation then throws facehex::Cancelled at its next check.
#include <functional>
#include <stdexcept>
#include <string>

namespace facehex {

using ProgressCallback = std::function<bool(const std::string& stage, double fraction)>;

struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled") {}
};

inline void report_progress(const ProgressCallback& progress, const std::string& stage, double fraction) {
  if (progress && !progress(stage, fraction)) throw Cancelled();
}

// A sub-stage's progress mapped into [lo, hi] of the whole job, under its own stage name, or under `stage` if given.
inline ProgressCallback sub_progress(const ProgressCallback& progress, double lo, double hi,
                                     const std::string& stage = "") {
  if (!progress) return {};
  return [=](const std::string& s, double f) { return progress(stage.empty() ? s : stage, lo + (hi - lo) * f); };
}

}  // namespace facehex
