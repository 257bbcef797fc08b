#include "app/cli_args.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "core/util/error.h"
#include "core/workflow/thread_count.h"

namespace facehex::cli {

Args::Args(std::string command, std::string summary) : command_(std::move(command)), summary_(std::move(summary)) {
  option("threads", "threads of this process: OpenMP loops, OpenBLAS, VTK imaging (default: all cores)");
}

Args& Args::positional(const std::string& name, const std::string& help, bool required) {
  specs_.push_back({name, help, "", false, required, true});
  return *this;
}

Args& Args::option(const std::string& name, const std::string& help, const std::string& default_value) {
  specs_.push_back({name, help, default_value, false, false, false});
  if (!default_value.empty()) values_[name] = default_value;
  return *this;
}

Args& Args::flag(const std::string& name, const std::string& help) {
  specs_.push_back({name, help, "", true, false, false});
  return *this;
}

bool Args::parse(const std::vector<std::string>& argv) {
  const std::string subject = "facehex " + command_;
  std::vector<const Spec*> positionals;
  for (const auto& s : specs_)
    if (s.positional) positionals.push_back(&s);
  size_t next_positional = 0;
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a == "--help" || a == "-h") {
      std::cout << usage();
      return false;
    }
    if (a.rfind("--", 0) == 0 || (a.size() == 2 && a[0] == '-' && a != "-")) {
      const std::string name = a == "-o" ? "output" : a.substr(2);
      const auto spec =
          std::find_if(specs_.begin(), specs_.end(), [&](const Spec& s) { return !s.positional && s.name == name; });
      if (spec == specs_.end()) throw UsageError(subject, "unknown option " + a + " (see --help)");
      if (spec->is_flag) {
        values_[name] = "1";
        continue;
      }
      if (i + 1 >= argv.size()) throw UsageError(subject, "option " + a + " needs a value");
      values_[name] = argv[++i];
      continue;
    }
    if (next_positional < positionals.size())
      values_[positionals[next_positional++]->name] = a;
    else if (last_repeats_ && !positionals.empty())
      rest_.push_back(a);
    else
      throw UsageError(subject, "unexpected argument '" + a + "' (see --help)");
  }
  for (const auto* p : positionals)
    if (p->required && !values_.count(p->name)) throw UsageError(subject, "missing " + p->name + " (see --help)");
  if (has("threads")) set_thread_count(integer("threads", 1, kMostThreads));
  return true;
}

std::string Args::usage() const {
  std::ostringstream os;
  os << "usage: facehex " << command_;
  for (const auto& s : specs_)
    if (s.positional) os << (s.required ? " " + s.name : " [" + s.name + "]");
  os << " [options]\n\n" << summary_ << "\n";
  // The command's own first; --threads, which every command has (the first spec), last.
  std::vector<Spec> listed(specs_.begin() + 1, specs_.end());
  listed.push_back(specs_.front());
  for (const auto& s : listed) {
    std::string left = s.positional ? "  " + s.name : "  --" + s.name + (s.is_flag ? "" : " VALUE");
    if (s.name == "output" && !s.positional) left = "  -o, --output VALUE";
    os << left << std::string(left.size() < 30 ? 30 - left.size() : 1, ' ') << s.help;
    if (!s.default_value.empty()) os << " (default: " << s.default_value << ")";
    os << "\n";
  }
  return os.str();
}

bool Args::has(const std::string& name) const { return values_.count(name) > 0; }

std::string Args::get(const std::string& name) const {
  const auto it = values_.find(name);
  return it == values_.end() ? std::string() : it->second;
}

double Args::number(const std::string& name) const {
  const std::string v = get(name);
  try {
    size_t used = 0;
    const double x = std::stod(v, &used);
    if (used != v.size()) throw std::invalid_argument(v);
    return x;
  } catch (const std::exception&) {
    throw UsageError("facehex " + command_, "--" + name + " expects a number, got '" + v + "'");
  }
}

int Args::integer(const std::string& name) const {
  const double x = number(name);
  if (!(std::abs(x) < 2147483647.0) || x != std::floor(x))
    throw UsageError("facehex " + command_, "--" + name + " expects an integer, got '" + get(name) + "'");
  return static_cast<int>(x);
}

double Args::number(const std::string& name, double least, double most) const {
  const double x = number(name);
  if (!(x >= least && x <= most)) {
    std::ostringstream range;
    range << least << " to " << most;
    throw UsageError("facehex " + command_,
                     "--" + name + " expects a number from " + range.str() + ", got '" + get(name) + "'");
  }
  return x;
}

int Args::integer(const std::string& name, int least, int most) const {
  number(name, least, most);
  return integer(name);
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

}  // namespace facehex::cli
