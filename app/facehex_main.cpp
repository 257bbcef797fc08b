// facehex: the command-line tool. Never links Qt.
#include <cstring>
#include <functional>
#include <iostream>
#include <map>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "core/util/allocator_tuning.h"
#include "core/util/error.h"
#include "core/util/progress.h"

namespace {

struct Command {
  std::function<int(const facehex::cli::Argv&)> run;
  const char* summary;
};

const std::map<std::string, Command>& commands() {
  using namespace facehex::cli;
  static const std::map<std::string, Command> table = {
      {"info", {cmd_info, "sizes, cell types, bounding box, volume and sides of a mesh"}},
      {"convert", {cmd_convert, "convert a mesh between formats (a closed surface is tetrahedralized)"}},
      {"sides", {cmd_sides, "label the six sides of a layered hex shell (for building a standard)"}},
      {"fields", {cmd_fields, "compute the three harmonic fields and the parameterization of a model"}},
      {"map", {cmd_map, "map a standard hex mesh onto a patient model"}},
      {"quality", {cmd_quality, "element quality of a hex mesh (and distortion against its standard)"}},
      {"run", {cmd_run, "end to end: patient model -> parameterization -> patient hex mesh + report"}},
      {"standards", {cmd_standards, "list the bundled standard meshes"}},
      {"template", {cmd_template, "build a new standard hex mesh from a reference model (CT, tet model)"}},
      {"segment", {cmd_segment, "head CT -> labelled patient tet model of the facial soft tissue"}},
      {"constraints", {cmd_constraints, "sides + feature constraints at the facial landmarks of a model"}},
      {"bench", {cmd_bench, "time each stage of a transfer for patients of several sizes"}},
      {"compare", {cmd_compare, "harmonic transfer vs the mesh-matching baseline: report, tables, plots"}},
      {"cohort-report", {cmd_cohort_report, "the report of a cohort meshed by workflow/Snakefile: table, plots"}},
  };
  return table;
}

void print_usage() {
  std::cout << "usage: facehex COMMAND [options]   (facehex COMMAND --help for each)\n\n"
               "Patient-specific hexahedral meshes of the facial soft tissue by harmonic-field volumetric mapping.\n\n"
               "commands:\n";
  for (const auto& [name, c] : commands())
    std::cout << "  " << name << std::string(name.size() < 14 ? 14 - name.size() : 1, ' ') << c.summary << "\n";
  std::cout << "\n'facehex run -o OUT' runs the bundled demo.\n";
}

}  // namespace

int main(int argc, char** argv) {
  facehex::keep_freed_memory_for_reuse();
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    print_usage();
    return argc < 2 ? 2 : 0;
  }
  if (!std::strcmp(argv[1], "--version")) {
    std::cout << "facehex " << FACEHEX_VERSION << "\n";
    return 0;
  }
  const auto it = commands().find(argv[1]);
  if (it == commands().end()) {
    std::cerr << "facehex: unknown command '" << argv[1] << "' (see facehex --help)\n";
    return 2;
  }
  try {
    return it->second.run(facehex::cli::Argv(argv + 2, argv + argc));
  } catch (const facehex::cli::UsageError& e) {
    std::cerr << "\nerror: " << e.what() << "\n";
    return 2;
  } catch (const facehex::Error& e) {
    std::cerr << "\nerror: " << e.what() << "\n";
  } catch (const facehex::Cancelled&) {
    std::cerr << "\ncancelled\n";
  } catch (const std::exception& e) {
    std::cerr << "\nerror: " << e.what() << "\n";
  }
  return 1;
}
