// The commands of `cmaps`, one file each: each reads its inputs, computes,
// writes its outputs and fills `out`; failures are thrown.
#pragma once

#include "arguments.h"
#include "outcome.h"

namespace cmaps::cli {

void run_check(const Arguments& args, Outcome& out);
void run_sphere(const Arguments& args, Outcome& out);
void run_constrained(const Arguments& args, Outcome& out);
void run_consistent(const Arguments& args, Outcome& out);
void run_intersurface(const Arguments& args, Outcome& out);
void run_transfer(const Arguments& args, Outcome& out);

}  // namespace cmaps::cli
