// The segmented zlib stream behind PNG's IDAT data (image/parallel_deflate):
// zlib's own inflate reads it back whole, its back-references reach across
// segments and calls, and its bytes depend neither on the thread count nor
// on how the rows are split into calls.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <zlib.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include "image/parallel_deflate.hpp"

using holoray::formats::ParallelDeflate;

namespace {

// Rows of `row_bytes` from `data`, added in calls of the given row counts;
// the whole stream.
std::vector<uint8_t> deflate_rows(const std::vector<uint8_t>& data, size_t row_bytes, const std::vector<size_t>& calls,
                                  size_t segment_bytes, int level = 1) {
  ParallelDeflate d(level, Z_DEFAULT_STRATEGY, segment_bytes);
  std::vector<uint8_t> out;
  size_t row = 0;
  for (size_t rows : calls) {
    const uint8_t* base = data.data() + row * row_bytes;
    d.add_rows(
        rows, row_bytes,
        [&](size_t first, size_t count, uint8_t* dst) { std::memcpy(dst, base + first * row_bytes, count * row_bytes); },
        [&](const uint8_t* p, size_t n) { out.insert(out.end(), p, p + n); });
    row += rows;
  }
  const std::vector<uint8_t> tail = d.finish();
  out.insert(out.end(), tail.begin(), tail.end());
  return out;
}

std::vector<uint8_t> inflate_all(const std::vector<uint8_t>& stream, size_t expect) {
  std::vector<uint8_t> back(expect + 1);
  uLongf n = static_cast<uLongf>(back.size());
  const int rc = uncompress(back.data(), &n, stream.data(), static_cast<uLong>(stream.size()));
  EXPECT_EQ(rc, Z_OK);  // also checks the header and the Adler-32
  back.resize(n);
  return back;
}

// 100 KiB of text-like bytes whose second half repeats the first at a
// distance of 2000 bytes, under deflate's 32 KiB reach, and a random tail.
std::vector<uint8_t> sample(size_t n) {
  std::vector<uint8_t> v(n);
  uint32_t state = 7;
  for (size_t k = 0; k < n; ++k) {
    state = state * 1664525u + 1013904223u;
    v[k] = k >= 2000 && k < n / 2 + 2000 ? v[k - 2000] : static_cast<uint8_t>('a' + (state >> 24) % 20);
  }
  return v;
}

}  // namespace

TEST(ParallelDeflate, StreamInflatesToTheRowsAcrossSegmentsAndCalls) {
  const std::vector<uint8_t> data = sample(100 * 1000);
  // 100-byte rows in segments of 7 rows, added 1, 0, 333 and 666 rows at a time.
  const std::vector<uint8_t> z = deflate_rows(data, 100, {1, 0, 333, 666}, 700);
  EXPECT_EQ(inflate_all(z, data.size()), data);
  // Level 0 (stored blocks) and 9 make valid streams too.
  for (int level : {0, 9}) EXPECT_EQ(inflate_all(deflate_rows(data, 100, {1000}, 700, level), data.size()), data) << level;
}

TEST(ParallelDeflate, BackReferencesReachAcrossSegments) {
  // Each 2000-byte segment of the first half repeats the one before: primed
  // with the bytes before it, a segment costs a few bytes; alone, a full
  // segment's worth. So the stream stays within a few bytes per segment of
  // one serial deflate at the same level.
  const std::vector<uint8_t> data = sample(100 * 1000);
  const std::vector<uint8_t> z = deflate_rows(data, 100, {1000}, 2000);
  std::vector<uint8_t> serial(compressBound(static_cast<uLong>(data.size())));
  uLongf n = static_cast<uLongf>(serial.size());
  ASSERT_EQ(compress2(serial.data(), &n, data.data(), static_cast<uLong>(data.size()), 1), Z_OK);
  const size_t segments = data.size() / 2000;
  EXPECT_LT(z.size(), n + 16 * segments) << "serial " << n;
}

TEST(ParallelDeflate, BytesDoNotDependOnTheThreadCount) {
  const std::vector<uint8_t> data = sample(100 * 1000);
  const std::vector<uint8_t> many = deflate_rows(data, 100, {500, 500}, 1500);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  EXPECT_EQ(deflate_rows(data, 100, {500, 500}, 1500), many);
}

// A giant EIA arrives band by band (mpirun render): however the rows are
// split into calls, the segments and so the bytes are those of one call.
TEST(ParallelDeflate, BytesDoNotDependOnHowTheRowsArrive) {
  const std::vector<uint8_t> data = sample(100 * 1000);
  const std::vector<uint8_t> whole = deflate_rows(data, 100, {1000}, 1500);
  EXPECT_EQ(deflate_rows(data, 100, {1, 0, 333, 666}, 1500), whole);
  EXPECT_EQ(deflate_rows(data, 100, {7, 7, 986}, 1500), whole);
  std::vector<size_t> ones(1000, 1);
  EXPECT_EQ(deflate_rows(data, 100, ones, 1500), whole);
  // Fewer rows than a segment in all: everything goes out in finish().
  const std::vector<uint8_t> small(data.begin(), data.begin() + 1000);
  EXPECT_EQ(inflate_all(deflate_rows(small, 100, {4, 6}, 1500), small.size()), small);
}

TEST(ParallelDeflate, NoRowsIsAnEmptyStream) {
  EXPECT_TRUE(inflate_all(deflate_rows({}, 10, {}, 100), 0).empty());
}

TEST(ParallelDeflate, RefusesBadSettings) {
  EXPECT_THROW(ParallelDeflate(10, Z_DEFAULT_STRATEGY, 100), std::invalid_argument);
  EXPECT_THROW(ParallelDeflate(1, Z_DEFAULT_STRATEGY, 0), std::invalid_argument);
  ParallelDeflate d(1, Z_DEFAULT_STRATEGY, 100);
  auto fill = [](size_t, size_t count, uint8_t* dst) { std::memset(dst, 1, count * 10); };
  auto sink = [](const uint8_t*, size_t) {};
  d.add_rows(2, 10, fill, sink);
  EXPECT_THROW(d.add_rows(2, 11, fill, sink), std::invalid_argument);  // rows keep one size
}
