#pragma once
// One decoded AVFrame to the image the graph's source wants, freshly allocated for every frame:
//  - gray, from a pixel format with an 8-bit luma plane (yuv420p, yuvj420p, yuv422p, yuv444p, nv12,
//    nv21, gray, ...): the Y plane itself, expanded to full range when the video is limited range
//    (kernels/luma_range.hpp). No colour conversion at all.
//  - BGR: swscale called as OpenCV 4.6's FFmpeg back end calls it (cap_ffmpeg_impl.hpp,
//    retrieveFrame): a context at the decoder's coded size, SWS_BICUBIC, the default (BT.601)
//    matrix, into a BGR24 buffer with 32-byte aligned rows, copied out. The same call gives the same
//    bytes, so frames equal cv::VideoCapture's (swscale's x86 code picks its path by width and row
//    stride, hence the same buffer shape, not just the same flags).
//  - gray from any other pixel format (RGB, packed YUV such as yuyv422, more than 8 bits): that
//    BGR, then cv::cvtColor BGR2GRAY, as neopipe's gray was before.
// One deliberate difference from OpenCV: a frame flagged full range (AVCOL_RANGE_JPEG) in a pixel
// format that swscale takes for limited range (yuv420p from HEVC or VP9, say) is converted as full
// range. OpenCV ignores the flag and stretches such video's contrast; the two agree on every other
// video (yuvj* formats and gray are full range to swscale already).

#include <opencv2/core/mat.hpp>

#include "pipeline/io/frame_source.hpp"
#include "pipeline/io/libav_handles.hpp"

namespace neopipe::pipeline::io::libav {

/// True for pixel formats whose first plane is 8-bit luma, one byte per pixel.
bool has_luma_plane(AVPixelFormat format);
/// True when the frame's luma spans 0..255 (full, "JPEG" range) rather than 16..235.
bool is_full_range(const AVFrame& frame);

class FrameConverter {
 public:
  explicit FrameConverter(ColorFormat format) : format_(format) {}
  /// CV_8UC1 or CV_8UC3 of frame.width x frame.height. `codec` gives the coded size swscale is set
  /// up with, as OpenCV does.
  cv::Mat convert(const AVFrame& frame, const AVCodecContext& codec);

 private:
  cv::Mat luma(const AVFrame& frame) const;
  /// A view of the frame as BGR in bgr_, valid until the next call.
  cv::Mat bgr_view(const AVFrame& frame, const AVCodecContext& codec);

  ColorFormat format_;
  SwsContextPtr sws_;
  FramePtr bgr_;  // swscale's output buffer, kept between frames as OpenCV keeps it
};

}  // namespace neopipe::pipeline::io::libav
