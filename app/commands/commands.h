#pragma once
// The facehex sub-commands, one file each in this folder. Each takes its arguments (after the command name) and returns
// the exit code; errors are thrown as facehex::Error and printed by main.
#include <string>
#include <vector>

namespace facehex::cli {

using Argv = std::vector<std::string>;

int cmd_info(const Argv& argv);
int cmd_convert(const Argv& argv);
int cmd_sides(const Argv& argv);
int cmd_fields(const Argv& argv);
int cmd_map(const Argv& argv);
int cmd_quality(const Argv& argv);
int cmd_run(const Argv& argv);
int cmd_standards(const Argv& argv);
int cmd_template(const Argv& argv);
int cmd_bench(const Argv& argv);
int cmd_constraints(const Argv& argv);
int cmd_segment(const Argv& argv);
int cmd_compare(const Argv& argv);
int cmd_cohort_report(const Argv& argv);

}  // namespace facehex::cli
