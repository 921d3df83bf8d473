#pragma once
// The daemon's GRAM part, from the config's gram block: the model worker
// pool with its engine, the environment the vehicle knows (read back from
// the store), and the way its changes reach the store. Defaults live here
// and in packaging/acommsd.conf (`acommsd --example-config`).

#include <memory>
#include <string>

#include "acomms/v1/config.pb.h"
#include "gram/model_pool.h"
#include "gram/vehicle_environment.h"
#include "service/gram_service.h"
#include "store/group_commit_writer.h"
#include "store/sqlite.h"

namespace acomms::node {

struct GramParts {
  std::unique_ptr<gram::VehicleEnvironment> environment;
  std::unique_ptr<gram::ModelPool> pool;
};

// Throws std::runtime_error naming the gram.* setting and its bound.
// `db` is read on the calling thread (before the writer owns it).
GramParts make_gram(const v1::GramConfig& config, const std::string& data_dir, store::Database& db);

// Saves the state on the writer thread; `done` runs once committed or failed.
service::SaveEnvironment save_environment_to(store::GroupCommitWriter& writer);

}  // namespace acomms::node
