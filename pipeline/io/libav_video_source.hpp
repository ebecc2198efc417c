#pragma once
// Frames from a video file, decoded by FFmpeg's libraries directly (libavformat, libavcodec,
// libswscale). Gray frames come from the decoder's luma plane with no colour conversion; BGR frames
// are converted as cv::VideoCapture converts them (see libav_frame_converter.hpp).
//
// Behaves as cv::VideoCapture(path, CAP_FFMPEG) in what it reads: the first video stream (cover
// pictures skipped), the same frames in the same order, the frame rate and frame count it reports,
// frames turned as the file's display matrix says (the way FFmpeg's tools turn them; OpenCV 4.6
// turns 90 and 270 degree videos the other way round). Its decoder threads differ on small machines
// only (decoder_threads).
//
// FFmpeg's own log lines are off; set NEOPIPE_FFMPEG_LOGLEVEL to an FFmpeg level (quiet, panic,
// fatal, error, warning, info, verbose, debug, trace, or its number) to see them on stderr.

#include <memory>
#include <string>

#include "pipeline/io/frame_source.hpp"

namespace neopipe::pipeline::io {

/// FFmpeg decoder threads for a machine with `cores` hardware threads: one per core, at most 16, as
/// cv::VideoCapture sets it; but 1 on one or two cores, where FFmpeg's frame threads cost a decoded
/// picture each and gain the run nothing (see the definition).
int decoder_threads(int cores);

class LibavVideoSource final : public FrameSource {
 public:
  /// Opens the file and decodes its first frame. Throws SourceError naming the file and the cause
  /// when it cannot be read, is not a video, holds no video stream, or no frame decodes.
  LibavVideoSource(std::string path, ColorFormat format);
  ~LibavVideoSource() override;
  LibavVideoSource(const LibavVideoSource&) = delete;
  LibavVideoSource& operator=(const LibavVideoSource&) = delete;

  /// Throws SourceError if the stream stops short of the frame count its container declares, or a
  /// frame's size differs from the first's.
  std::optional<SourceFrame> next() override;
  std::string description() const override;
  double fps() const override;
  std::optional<std::int64_t> frame_count() const override;

 private:
  struct Impl;  // keeps FFmpeg's headers out of everything that includes this one
  std::unique_ptr<Impl> impl_;
};

}  // namespace neopipe::pipeline::io
