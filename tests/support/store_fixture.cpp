#include "store_fixture.h"

namespace acomms::testing {

void StoreFixture::open_store() { open_store(dir_ / "data"); }

void StoreFixture::open_store(const std::filesystem::path& data_dir) {
  store_ = std::make_unique<store::Store>(data_dir.string());
  writer_ = std::make_unique<store::GroupCommitWriter>(store_->db());
  journal_ = std::make_unique<queue::SqliteJournal>(*writer_);
}

void StoreFixture::close_store() {
  journal_.reset();
  writer_.reset();
  store_.reset();
}

}  // namespace acomms::testing
