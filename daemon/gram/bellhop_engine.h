// BELLHOP itself as the pool's engine, for users who want its answers.
//
// Problem: BELLHOP reads and writes files beside its input and may fail,
// hang or write a field in either .shd layout; the daemon's service unit
// may write only under its data dir. Decision: each run gets a fresh
// private directory (mode 0700) under `work_root`, the environment is
// written there (bellhop_export.h), `executable ROOT` runs in it with the
// time limit and the run's cancel token (external_process.h), the .shd is
// read (shd_file.h) and the directory removed. A non-zero exit, a signal,
// the time limit or an unreadable .shd is an EngineError whose text is the
// program's own output, verbatim. Thread-safe (one directory per run).
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "gram/model_engine.h"
#include "gram/shd_file.h"

namespace acomms::gram {

struct BellhopOptions {
  std::string executable;
  std::string work_root;  // created if missing
  std::chrono::duration<double> timeout{60.0};
};

std::unique_ptr<ModelEngine> make_bellhop_engine(const BellhopOptions& options);

// The TL of a .shd field for the environment's receivers; throws EngineError
// when the field's grid is not the environment's.
TransmissionLoss tl_from_shd(const ShdField& field, const Environment& env);

}  // namespace acomms::gram
