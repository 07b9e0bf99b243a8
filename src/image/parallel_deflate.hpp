// holoray/image, internal: one zlib stream (RFC 1950) deflated on every
// core, as pigz does. The input, rows of one size, is cut into segments of
// whole rows; each is deflated on its own (raw deflate, RFC 1951) with the 32 KiB before it
// as its dictionary and ends in a sync flush (an empty stored block: byte
// aligned, not final), so the segments' bytes joined in order are one valid
// stream whose back-references reach across segments as a serial deflate's
// do. The file is a few bytes per segment larger than a serial deflate's
// at the same level (the flush markers) and its bytes depend only on the
// input, its rows, the level, the strategy and the segment size, never on
// the thread count or on how the rows arrive. PNG's IDAT data is such a stream (png_format.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace holoray::formats {

class ParallelDeflate {
 public:
  /// zlib's level (0..9) and strategy (Z_*); segments of about
  /// `segment_bytes` (> 0) of input, in whole rows. Throws
  /// std::invalid_argument for a bad level or size.
  ParallelDeflate(int level, int strategy, size_t segment_bytes);

  /// Writes rows [first, first + count) of this call's input, count *
  /// row_bytes bytes, to dst. Called from several threads at once, and
  /// twice for some rows (the rows before a segment are its dictionary).
  /// It must not start parallel work of its own: a thread waiting on it
  /// could pick up another segment and reuse the buffer dst lies in.
  using RowSource = std::function<void(size_t first, size_t count, uint8_t* dst)>;
  /// Receives the stream's next bytes, in order.
  using Sink = std::function<void(const uint8_t* data, size_t bytes)>;

  /// The stream's bytes for `rows` more rows of `row_bytes` bytes each,
  /// handed to `sink` a segment at a time (the zlib header in front of the
  /// first). Only whole segments go out; the rows after the last one (less
  /// than a segment) are kept for the next call or finish(), so the bytes do
  /// not depend on how the rows are split into calls either. The rows are
  /// made segment by segment in small buffers, never all at once. Throws std::runtime_error where zlib fails (out of memory),
  /// std::invalid_argument for a row size different from the last call's.
  void add_rows(size_t rows, size_t row_bytes, const RowSource& source, const Sink& sink);

  /// The end of the stream: the rows held back as the last segment, an empty
  /// final block and the Adler-32 of all the input (the header in front when
  /// nothing went out before).
  std::vector<uint8_t> finish();

 private:
  int level_, strategy_;
  size_t segment_bytes_;
  size_t row_bytes_ = 0;
  bool started_ = false;
  uint32_t adler_;
  // The zlib header into the 2 bytes left free at the front of the
  // stream's first output, once.
  void header_into(std::vector<uint8_t>& first);
  // A segment whose `before_bytes` of buf[] precede its n bytes, with
  // window_ as the dictionary where those are under 32 KiB.
  std::vector<uint8_t> deflate_with_window(const uint8_t* buf, size_t before_bytes, size_t n,
                                           size_t reserve_front) const;
  std::vector<uint8_t> window_;   // the last 32 KiB of input deflated so far: the next segment's dictionary
  std::vector<uint8_t> pending_;  // rows not yet deflated: fewer than a segment's
};

}  // namespace holoray::formats
