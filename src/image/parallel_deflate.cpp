#include "image/parallel_deflate.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "util/parallel.hpp"

namespace holoray::formats {

namespace {

constexpr size_t kWindow = 32768;  // deflate's reach back (RFC 1951 §2)
constexpr size_t kMaxSegment = std::numeric_limits<uInt>::max() / 2;  // zlib counts input in a 32-bit uInt

// The last 32 KiB of `a` followed by b[0, n).
std::vector<uint8_t> last_window(const std::vector<uint8_t>& a, const uint8_t* b, size_t n) {
  if (n >= kWindow) return std::vector<uint8_t>(b + n - kWindow, b + n);
  const size_t from_a = std::min(a.size(), kWindow - n);
  std::vector<uint8_t> w(a.end() - static_cast<ptrdiff_t>(from_a), a.end());
  w.insert(w.end(), b, b + n);
  return w;
}

// A thread's raw deflate state, kept from segment to segment: zlib's
// quarter megabyte of tables is touched once per thread, not once per
// segment (fresh pages cost more than the compression on a 2-core VM).
class Deflater {
 public:
  ~Deflater() {
    if (ready_) deflateEnd(&z_);
  }
  z_stream& reset(int level, int strategy) {
    if (ready_ && (level != level_ || strategy != strategy_)) deflateEnd(&z_), ready_ = false;
    if (!ready_) {
      z_ = z_stream{};
      if (deflateInit2(&z_, level, Z_DEFLATED, -15, 8, strategy) != Z_OK) throw std::runtime_error("out of memory");
      ready_ = true, level_ = level, strategy_ = strategy;
    } else if (deflateReset(&z_) != Z_OK) {
      throw std::runtime_error("zlib failed to reset");
    }
    return z_;
  }

 private:
  z_stream z_{};
  bool ready_ = false;
  int level_ = 0, strategy_ = 0;
};

// One segment: raw deflate primed with `dict`, ended by a sync flush;
// `reserve_front` bytes left free in front of it (for the zlib header).
std::vector<uint8_t> deflate_segment(const uint8_t* dict, size_t dict_n, const uint8_t* in, size_t n, int level,
                                     int strategy, size_t reserve_front) {
  thread_local Deflater deflater;
  z_stream& z = deflater.reset(level, strategy);
  if (dict_n > 0 && deflateSetDictionary(&z, dict, static_cast<uInt>(dict_n)) != Z_OK)
    throw std::runtime_error("zlib refused the dictionary");
  // Compressed into a buffer kept per thread (a fresh one, zero-filled,
  // would cost more than deflating), then copied out at its size.
  thread_local std::vector<uint8_t> scratch;
  scratch.resize(std::max(scratch.size(), reserve_front + deflateBound(&z, static_cast<uLong>(n)) + 64));
  size_t used = reserve_front;
  z.next_in = const_cast<Bytef*>(in);
  z.avail_in = static_cast<uInt>(n);
  for (;;) {
    z.next_out = scratch.data() + used;
    z.avail_out = static_cast<uInt>(std::min(scratch.size() - used, kMaxSegment));
    const int rc = deflate(&z, Z_SYNC_FLUSH);
    if (rc != Z_OK && rc != Z_BUF_ERROR) throw std::runtime_error("zlib failed to compress");
    used = scratch.size() - z.avail_out;
    // Done once the input is in and the flush left output space over.
    if (z.avail_in == 0 && z.avail_out != 0) break;
    scratch.resize(scratch.size() * 2);
  }
  return std::vector<uint8_t>(scratch.begin(), scratch.begin() + static_cast<ptrdiff_t>(used));
}

// RFC 1950 §2.2: CMF 0x78 (deflate, 32 KiB window), FLEVEL as zlib sets it,
// and FCHECK, which makes CMF*256 + FLG a multiple of 31.
std::vector<uint8_t> zlib_header(int level, int strategy) {
  const unsigned cmf = 0x78;
  const unsigned flevel = strategy >= Z_HUFFMAN_ONLY || level < 2 ? 0 : level < 6 ? 1 : level == 6 ? 2 : 3;
  const unsigned flg = flevel << 6;
  return {static_cast<uint8_t>(cmf), static_cast<uint8_t>(flg + 31 - (cmf * 256 + flg) % 31)};
}

}  // namespace

ParallelDeflate::ParallelDeflate(int level, int strategy, size_t segment_bytes)
    : level_(level), strategy_(strategy), segment_bytes_(segment_bytes), adler_(adler32(0, nullptr, 0)) {
  if (level < 0 || level > 9) throw std::invalid_argument("zlib levels are 0 to 9");
  if (segment_bytes == 0 || segment_bytes > kMaxSegment)
    throw std::invalid_argument("a deflate segment holds 1 byte to 2 GiB");
}

void ParallelDeflate::add_rows(size_t rows, size_t row_bytes, const RowSource& source, const Sink& sink) {
  if (rows == 0) return;
  if (row_bytes == 0 || row_bytes > kMaxSegment || (row_bytes_ != 0 && row_bytes != row_bytes_))
    throw std::invalid_argument("a deflate stream's rows keep one size of 1 byte to 2 GiB");
  row_bytes_ = row_bytes;
  const size_t per_segment = std::max<size_t>(1, segment_bytes_ / row_bytes);
  const size_t dict_rows = (kWindow + row_bytes - 1) / row_bytes;
  // This call's input is the rows held back by the last call followed by
  // the new ones; only whole segments go out, so where the calls cut the
  // rows never moves a segment boundary.
  const size_t held = pending_.size() / row_bytes, total = held + rows;
  const size_t count = total / per_segment;
  auto fetch = [&](size_t first, size_t n, uint8_t* dst) {
    if (first < held) {
      const size_t from_held = std::min(n, held - first);
      std::memcpy(dst, pending_.data() + first * row_bytes, from_held * row_bytes);
      dst += from_held * row_bytes, first += from_held, n -= from_held;
    }
    if (n > 0) source(first - held, n, dst);
  };
  std::vector<std::vector<uint8_t>> out(count);
  std::vector<uLong> adlers(count);
  const size_t header = started_ ? 0 : 2;
  parallel_for_n(static_cast<int>(count), 0, [&](int slot) {
    const size_t k = static_cast<size_t>(slot);
    const size_t first = k * per_segment;
    // The rows before the segment (its dictionary) and the segment's, made
    // in one buffer per thread; the window of the input already deflated
    // joins in where this call has not yet 32 KiB before the segment.
    const size_t before = std::min(first, dict_rows);
    thread_local std::vector<uint8_t> buf;
    buf.resize((before + per_segment) * row_bytes);
    fetch(first - before, before + per_segment, buf.data());
    out[k] = deflate_with_window(buf.data(), before * row_bytes, per_segment * row_bytes, k == 0 ? header : 0);
    adlers[k] = adler32(adler32(0, nullptr, 0), buf.data() + before * row_bytes, static_cast<uInt>(per_segment * row_bytes));
  });
  if (count > 0) header_into(out[0]);
  for (size_t k = 0; k < count; ++k) {
    adler_ = static_cast<uint32_t>(adler32_combine(adler_, adlers[k], static_cast<z_off_t>(per_segment * row_bytes)));
    sink(out[k].data(), out[k].size());
  }
  // The last 32 KiB of what went out: the next segment's dictionary; the
  // rows after the last whole segment wait for the next call or finish().
  const size_t sent = count * per_segment;
  if (count > 0) {
    const size_t tail_rows = std::min(sent, dict_rows);
    std::vector<uint8_t> tail(tail_rows * row_bytes);
    fetch(sent - tail_rows, tail_rows, tail.data());
    window_ = last_window(window_, tail.data(), tail.size());
  }
  std::vector<uint8_t> rest((total - sent) * row_bytes);
  fetch(sent, total - sent, rest.data());
  pending_ = std::move(rest);
}

std::vector<uint8_t> ParallelDeflate::deflate_with_window(const uint8_t* buf, size_t before_bytes, size_t n,
                                                          size_t reserve_front) const {
  const uint8_t* dict = buf;
  size_t dict_n = before_bytes;
  std::vector<uint8_t> joined;
  if (dict_n < kWindow && !window_.empty()) {
    joined = last_window(window_, buf, dict_n);
    dict = joined.data(), dict_n = joined.size();
  } else if (dict_n > kWindow) {
    dict += dict_n - kWindow, dict_n = kWindow;
  }
  return deflate_segment(dict, dict_n, buf + before_bytes, n, level_, strategy_, reserve_front);
}

void ParallelDeflate::header_into(std::vector<uint8_t>& first) {
  if (started_) return;
  const std::vector<uint8_t> h = zlib_header(level_, strategy_);
  std::copy(h.begin(), h.end(), first.begin());
  started_ = true;
}

std::vector<uint8_t> ParallelDeflate::finish() {
  // The rows held back (less than a segment) are the last segment.
  std::vector<uint8_t> tail(started_ ? 0 : 2);
  if (!pending_.empty()) {
    tail = deflate_with_window(pending_.data(), 0, pending_.size(), started_ ? 0 : 2);
    adler_ = static_cast<uint32_t>(adler32(adler_, pending_.data(), static_cast<uInt>(pending_.size())));
    pending_.clear();
  }
  header_into(tail);
  // A final fixed-Huffman block holding only its end code (RFC 1951 §3.2.6),
  // then the Adler-32 of the input, most significant byte first.
  const uint8_t end[6] = {0x03,
                          0x00,
                          static_cast<uint8_t>(adler_ >> 24),
                          static_cast<uint8_t>(adler_ >> 16),
                          static_cast<uint8_t>(adler_ >> 8),
                          static_cast<uint8_t>(adler_)};
  tail.insert(tail.end(), end, end + 6);
  return tail;
}

}  // namespace holoray::formats
