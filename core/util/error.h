#pragma once
// One exception type for every user-facing failure. The message is a single line,
// "SUBJECT: problem", where SUBJECT is the file (or stage) at fault; the CLI prints it
// as is and exits non-zero, the GUI shows it in a dialog.
#include <stdexcept>
#include <string>

namespace facehex {

class Error : public std::runtime_error {
 public:
  Error(const std::string& subject, const std::string& problem)
      : std::runtime_error(subject.empty() ? problem : subject + ": " + problem),
        subject_(subject),
        problem_(problem) {}
  const std::string& subject() const { return subject_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string subject_, problem_;
};

}  // namespace facehex
