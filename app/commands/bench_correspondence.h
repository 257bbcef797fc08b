#pragma once
// facehex bench --correspondence: the known-answer transfers of core/evaluation/correspondence_benchmark.h and their
// report (OUT/correspondence.md, OUT/correspondence.json, OUT/correspondence_skin_error.png).
#include "app/cli_args.h"

namespace facehex::cli {

// --correspondence, --output, --models, --deformation-models, --warps, --cts, --ct-seeds, --true-landmarks,
// --mapping-only.
void add_correspondence_options(Args& args);

// Runs the benchmark with the transfer options of `args` and writes the report; 0, or 1 when a case failed.
int correspondence_bench(const Args& args);

}  // namespace facehex::cli
