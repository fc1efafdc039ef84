// libFuzzer target: the .tvkhair reader (header, section table, checksums, sections, validate()). A file the
// reader accepts must validate and write back to bytes the reader accepts again. Each input is read twice: as
// given (the checksum and size checks) and with its checksums recomputed (everything behind them).
#include "fuzz_common.hpp"

using namespace tressvk;

namespace {

void read_one(std::span<const std::byte> bytes) {
  const asset::ReadResult info = asset::inspect(bytes);
  const asset::ReadResult r = asset::read(bytes);
  if (r.status == asset::ReadStatus::kIoError) fuzz::finding("read() of bytes reported an I/O error");
  if (!r.ok()) {
    if (r.error.empty()) fuzz::finding("a refused file without a message");
    return;
  }
  if (!info.ok()) fuzz::finding("read() accepted a file that inspect() refused: " + info.error);
  fuzz::check_asset(r.asset, "read()");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  read_one(fuzz::as_bytes(data, size));
  const std::vector<std::byte> fixed = fuzz::with_fixed_checksums(data, size);
  read_one(fixed);
  return 0;
}
