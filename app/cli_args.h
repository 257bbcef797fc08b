#pragma once
// A small command-line parser: positionals and --name VALUE / --flag options, each documented for --help.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/util/error.h"

namespace facehex::cli {

// A command line that cannot be run as given (unknown or missing option, bad value): exit code 2, as the README says.
class UsageError : public Error {
 public:
  using Error::Error;
};

class Args {
 public:
  // Every command also takes --threads N (kMostThreads at most), applied by parse() (core/workflow/thread_count.h).
  Args(std::string command, std::string summary);
  static constexpr int kMostThreads = 1024;

  Args& positional(const std::string& name, const std::string& help, bool required = true);
  Args& option(const std::string& name, const std::string& help, const std::string& default_value = "");
  Args& flag(const std::string& name, const std::string& help);
  // The last positional may be repeated: the values after the first are in rest(). Without this, a surplus
  // positional is an error (a mistyped glob must not turn an input into an output).
  Args& last_positional_repeats() {
    last_repeats_ = true;
    return *this;
  }

  // Parses argv (without the program and command names) and sets the process's thread count when --threads is given.
  // Returns false when --help was asked (usage printed); throws facehex::Error("facehex COMMAND", ...) on unknown
  // options, missing values or surplus positionals.
  bool parse(const std::vector<std::string>& argv);

  std::string usage() const;
  bool has(const std::string& name) const;  // positional or option given (or flag set)
  std::string get(const std::string& name) const;
  double number(const std::string& name) const;
  int integer(const std::string& name) const;
  // The same, checked to lie in [least, most] (options that scale the work: a typo must not start a run for days).
  double number(const std::string& name, double least, double most) const;
  int integer(const std::string& name, int least, int most) const;
  const std::vector<std::string>& rest() const { return rest_; }

 private:
  struct Spec {
    std::string name, help, default_value;
    bool is_flag = false, required = false, positional = false;
  };
  std::string command_, summary_;
  std::vector<Spec> specs_;
  std::map<std::string, std::string> values_;
  std::vector<std::string> rest_;  // repeated last positional
  bool last_repeats_ = false;
};

// The items of a comma-separated list ("a,b c,d" -> {"a", "b c", "d"}), empty ones dropped.
std::vector<std::string> split_commas(const std::string& text);

}  // namespace facehex::cli
