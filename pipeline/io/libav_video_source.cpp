#include "pipeline/io/libav_video_source.hpp"

extern "C" {
#include <libavutil/display.h>
}

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <opencv2/core.hpp>
#include <utility>

#include "pipeline/io/files.hpp"
#include "pipeline/io/libav_frame_converter.hpp"
#include "pipeline/io/libav_handles.hpp"

namespace neopipe::pipeline::io {
namespace {

// Consecutive packets or frames that fail to decode before the reader gives up; a damaged packet
// or two is skipped, as FFmpeg's own tools do. (OpenCV allows 64 failed decode attempts too.)
constexpr int kMaxDecodeErrors = 64;

// FFmpeg prints warnings about damaged streams itself, which would break neopipe's one-line
// errors and its table on stdout: quiet, unless NEOPIPE_FFMPEG_LOGLEVEL asks for them. The level
// is global to the process, so it is set again at every open (OpenCV's back end sets it too).
void set_ffmpeg_log_level() {
  static constexpr std::array<std::pair<const char*, int>, 9> kLevels{{{"quiet", AV_LOG_QUIET},
                                                                       {"panic", AV_LOG_PANIC},
                                                                       {"fatal", AV_LOG_FATAL},
                                                                       {"error", AV_LOG_ERROR},
                                                                       {"warning", AV_LOG_WARNING},
                                                                       {"info", AV_LOG_INFO},
                                                                       {"verbose", AV_LOG_VERBOSE},
                                                                       {"debug", AV_LOG_DEBUG},
                                                                       {"trace", AV_LOG_TRACE}}};
  int level = AV_LOG_QUIET;
  if (const char* env = std::getenv("NEOPIPE_FFMPEG_LOGLEVEL"); env != nullptr && *env != '\0') {
    char* end = nullptr;
    const long number = std::strtol(env, &end, 10);
    if (*end == '\0') {
      level = static_cast<int>(number);
    } else {
      for (const auto& [name, value] : kLevels) {
        if (std::strcmp(env, name) == 0) level = value;
      }
    }
  }
  av_log_set_level(level);
}

double to_double(AVRational r) {
  return r.num == 0 || r.den == 0 ? 0.0 : static_cast<double>(r.num) / r.den;
}

// The first video stream that is not a cover picture (OpenCV takes the first video stream).
int find_video_stream(const AVFormatContext& fmt) {
  for (unsigned i = 0; i < fmt.nb_streams; ++i) {
    const AVStream* s = fmt.streams[i];
    if (s->codecpar->codec_type == AVMEDIA_TYPE_VIDEO && (s->disposition & AV_DISPOSITION_ATTACHED_PIC) == 0) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

// Degrees clockwise the frames are to be turned for display, from the stream's display matrix (which
// holds the counter-clockwise angle): as FFmpeg's own tools and OpenCV after 4.6 turn them. OpenCV
// 4.6 takes the angle as clockwise and turns 90 and 270 degree videos the wrong way round.
int display_rotation(const AVStream& stream) {
  const std::uint8_t* matrix = av_stream_get_side_data(&stream, AV_PKT_DATA_DISPLAYMATRIX, nullptr);
  if (matrix == nullptr) return 0;
  const double counter_clockwise = av_display_rotation_get(reinterpret_cast<const std::int32_t*>(matrix));
  // A degenerate matrix (a zero scale) gives NaN, which cvRound turns into INT_MIN, whose negation
  // is undefined (found by fuzz/fuzz_video.cpp): such a matrix names no turn.
  if (!std::isfinite(counter_clockwise)) return 0;
  int angle = -cvRound(counter_clockwise);
  if (angle < 0) angle += 360;
  return angle;
}

}  // namespace

// Frame threading (MPEG-4, H.264, HEVC, ...) decodes one frame per thread, and each frame thread
// holds a picture and a decoder context of its own: for 1080p MPEG-4, 6.3 MiB of resident memory
// per thread beyond the first (about 4x that at 4K). On one or two cores neopipe's workers keep
// the cores busy already, and a second decoder thread did not make `neopipe run` faster; it only
// cost that memory (docs/video-measurements.md, "Anonymous memory", 2026-12-02). With more cores,
// frame threads let the one reader thread decode as fast as the workers process, so there it is
// OpenCV's choice: one thread per core, at most 16 (FFmpeg warns above that).
int decoder_threads(int cores) {
  return cores <= 2 ? 1 : std::min(cores, 16);
}

struct LibavVideoSource::Impl {
  std::string path;
  libav::FrameConverter converter;
  libav::FormatContextPtr format;
  libav::CodecContextPtr codec;
  libav::PacketPtr packet;
  libav::FramePtr frame;
  int stream = -1;
  int rotation = 0;
  double fps = 0;
  std::int64_t declared_frames = 0;  // what the container says, as OpenCV reads it; 0 if it does not say
  std::int64_t pos = 0;
  cv::Size size;                   // of the first decoded frame
  std::optional<cv::Mat> pending;  // the first frame, decoded at open to prove the file decodes
  bool draining = false;           // the demuxer is done; the decoder hands out what it still holds
  bool ended = false;
  int last_error = 0;  // the last decoding or reading error, for the message if the stream stops short

  Impl(std::string p, ColorFormat format_wanted);
  [[noreturn]] void fail(const std::string& cause) const { throw SourceError(path + ": " + cause); }
  bool decode_next();
  cv::Mat take_frame();
  void read_container_facts();
};

LibavVideoSource::Impl::Impl(std::string p, ColorFormat format_wanted) : path(std::move(p)), converter(format_wanted) {
  require_readable(path);
  set_ffmpeg_log_level();
  AVFormatContext* opened = nullptr;  // freed by FFmpeg itself if the open fails
  int r = avformat_open_input(&opened, path.c_str(), nullptr, nullptr);
  if (r < 0) fail("neither an image nor a video neopipe can read (FFmpeg: " + libav::error_text(r) + ")");
  format.reset(opened);
  r = avformat_find_stream_info(format.get(), nullptr);
  if (r < 0) fail("not a video neopipe can read (FFmpeg: " + libav::error_text(r) + ")");
  stream = find_video_stream(*format);
  if (stream < 0) fail("the file holds no video stream");
  const AVStream& st = *format->streams[stream];
  const AVCodec* decoder = avcodec_find_decoder(st.codecpar->codec_id);
  if (decoder == nullptr)
    fail(std::string("no decoder for its video codec ") + avcodec_get_name(st.codecpar->codec_id));
  codec.reset(avcodec_alloc_context3(decoder));
  packet.reset(av_packet_alloc());
  frame.reset(av_frame_alloc());
  if (!codec || !packet || !frame) throw std::bad_alloc();
  r = avcodec_parameters_to_context(codec.get(), st.codecpar);
  if (r < 0)
    fail("cannot set up the " + std::string(decoder->name) + " decoder (FFmpeg: " + libav::error_text(r) + ")");
  // Frame and slice threading are FFmpeg's defaults (see decoder_threads for the count).
  codec->thread_count = decoder_threads(cv::getNumberOfCPUs());
  r = avcodec_open2(codec.get(), decoder, nullptr);
  if (r < 0) fail("cannot open the " + std::string(decoder->name) + " decoder (FFmpeg: " + libav::error_text(r) + ")");
  read_container_facts();
  if (!decode_next()) fail("the video has no frames");
  size = {frame->width, frame->height};
  pending = take_frame();
}

// Frame rate and frame count as cv::VideoCapture reports them (CAP_PROP_FPS, CAP_PROP_FRAME_COUNT):
// the count is the container's, else duration x rate rounded.
void LibavVideoSource::Impl::read_container_facts() {
  AVStream& st = *format->streams[stream];
  fps = to_double(av_guess_frame_rate(format.get(), &st, nullptr));
  if (!std::isfinite(fps) || fps < 0) fps = 0;
  std::int64_t n = st.nb_frames;
  if (n == 0) {
    constexpr double kEpsilon = 0.000025;  // OpenCV's eps_zero
    double seconds = static_cast<double>(format->duration) / AV_TIME_BASE;
    if (seconds < kEpsilon) seconds = static_cast<double>(st.duration) * to_double(st.time_base);
    const double estimate = std::floor(seconds * fps + 0.5);
    n = std::isfinite(estimate) && estimate > 0 && estimate < 9e18 ? static_cast<std::int64_t>(estimate) : 0;
  }
  declared_frames = std::max<std::int64_t>(n, 0);
  rotation = display_rotation(st);
}

// The next decoded frame into `frame`; false at the end of the stream.
bool LibavVideoSource::Impl::decode_next() {
  int errors = 0;
  for (;;) {
    int r = avcodec_receive_frame(codec.get(), frame.get());
    if (r == 0) return true;
    if (r == AVERROR_EOF) return false;
    if (r != AVERROR(EAGAIN)) {  // a frame that failed to decode (threaded decoders report it here)
      last_error = r;
      if (++errors > kMaxDecodeErrors) return false;
      continue;
    }
    if (draining) return false;  // not reached: a drained decoder answers AVERROR_EOF
    r = av_read_frame(format.get(), packet.get());
    if (r < 0) {  // the end of the file, or a read error (a cut file): the decoder gives what it holds
      if (r != AVERROR_EOF) last_error = r;
      draining = true;
      avcodec_send_packet(codec.get(), nullptr);
      continue;
    }
    if (packet->stream_index != stream) {
      av_packet_unref(packet.get());
      continue;
    }
    r = avcodec_send_packet(codec.get(), packet.get());
    av_packet_unref(packet.get());
    if (r < 0 && r != AVERROR(EAGAIN)) {  // a damaged packet: skipped
      last_error = r;
      if (++errors > kMaxDecodeErrors) return false;
    }
  }
}

// The decoded frame as a fresh image in the wanted format, turned for display.
cv::Mat LibavVideoSource::Impl::take_frame() {
  const cv::Size decoded(frame->width, frame->height);
  if (decoded != size) {
    fail("frame " + std::to_string(pos) + " is " + size_text(decoded) + " but the video started at " + size_text(size));
  }
  cv::Mat image = converter.convert(*frame, *codec);
  av_frame_unref(frame.get());
  switch (rotation) {
    case 90:
      cv::rotate(image, image, cv::ROTATE_90_CLOCKWISE);
      break;
    case 180:
      cv::rotate(image, image, cv::ROTATE_180);
      break;
    case 270:
      cv::rotate(image, image, cv::ROTATE_90_COUNTERCLOCKWISE);
      break;
    default:
      break;
  }
  return image;
}

LibavVideoSource::LibavVideoSource(std::string path, ColorFormat format)
    : impl_(std::make_unique<Impl>(std::move(path), format)) {}

LibavVideoSource::~LibavVideoSource() = default;

std::string LibavVideoSource::description() const {
  return impl_->path;
}

double LibavVideoSource::fps() const {
  return impl_->fps;
}

std::optional<std::int64_t> LibavVideoSource::frame_count() const {
  if (impl_->declared_frames > 0) return impl_->declared_frames;
  return std::nullopt;
}

std::optional<SourceFrame> LibavVideoSource::next() {
  Impl& s = *impl_;
  if (s.ended) return std::nullopt;
  SourceFrame f;
  if (s.pending) {
    f.image = std::move(*s.pending);
    s.pending.reset();
  } else if (s.decode_next()) {
    f.image = s.take_frame();
  } else {
    s.ended = true;
    if (s.declared_frames > 0 && s.pos < s.declared_frames) {
      s.fail("decoding stopped at frame " + std::to_string(s.pos) + " of " + std::to_string(s.declared_frames) +
             " (truncated or corrupt video" +
             (s.last_error != 0 ? "; FFmpeg: " + libav::error_text(s.last_error) : std::string()) + ")");
    }
    return std::nullopt;
  }
  f.index = s.pos++;
  return f;
}

}  // namespace neopipe::pipeline::io
