#include "pipeline/io/libav_frame_converter.hpp"

extern "C" {
#include <libavutil/pixdesc.h>
}

#include <algorithm>
#include <cstring>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "kernels/luma_range.hpp"

namespace neopipe::pipeline::io::libav {
namespace {

// Row y of a plane; FFmpeg's line sizes may be negative (bottom-up pictures).
const std::uint8_t* plane_row(const AVFrame& f, int plane, int y) {
  return f.data[plane] + static_cast<std::ptrdiff_t>(y) * f.linesize[plane];
}

}  // namespace

bool has_luma_plane(AVPixelFormat format) {
  const AVPixFmtDescriptor* d = av_pix_fmt_desc_get(format);
  if (d == nullptr) return false;
  constexpr auto kNotLuma = AV_PIX_FMT_FLAG_RGB | AV_PIX_FMT_FLAG_PAL | AV_PIX_FMT_FLAG_BITSTREAM |
                            AV_PIX_FMT_FLAG_HWACCEL | AV_PIX_FMT_FLAG_FLOAT | AV_PIX_FMT_FLAG_BAYER;
  if ((d->flags & kNotLuma) != 0) return false;
  const AVComponentDescriptor& y = d->comp[0];
  return y.plane == 0 && y.step == 1 && y.offset == 0 && y.shift == 0 && y.depth == 8;
}

bool is_full_range(const AVFrame& frame) {
  switch (frame.format) {
    // The formats swscale itself treats as full range, whatever the frame says.
    case AV_PIX_FMT_YUVJ420P:
    case AV_PIX_FMT_YUVJ422P:
    case AV_PIX_FMT_YUVJ444P:
    case AV_PIX_FMT_YUVJ440P:
    case AV_PIX_FMT_YUVJ411P:
    case AV_PIX_FMT_GRAY8:
      return true;
    default:
      return frame.color_range == AVCOL_RANGE_JPEG;
  }
}

cv::Mat FrameConverter::convert(const AVFrame& frame, const AVCodecContext& codec) {
  const auto format = static_cast<AVPixelFormat>(frame.format);
  if (format_ == ColorFormat::gray && has_luma_plane(format)) return luma(frame);
  const cv::Mat view = bgr_view(frame, codec);
  if (format_ == ColorFormat::bgr) return view.clone();
  cv::Mat gray;
  cv::cvtColor(view, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

cv::Mat FrameConverter::luma(const AVFrame& frame) const {
  cv::Mat out(frame.height, frame.width, CV_8UC1);
  const bool full = is_full_range(frame);
  for (int y = 0; y < frame.height; ++y) {
    const std::uint8_t* src = plane_row(frame, 0, y);
    auto* dst = out.ptr<std::uint8_t>(y);
    if (full) {
      std::memcpy(dst, src, static_cast<size_t>(frame.width));
    } else {
      kernels::limited_to_full_luma_row(src, dst, frame.width);
    }
  }
  return out;
}

cv::Mat FrameConverter::bgr_view(const AVFrame& frame, const AVCodecContext& codec) {
  // OpenCV sets swscale up at the coded size (for old FFmpeg versions, it says) and converts the
  // frame's rows; the decoder's buffers are padded to at least that size.
  // (Never smaller than the frame, which the view below reads.)
  const int width = std::max(codec.coded_width, frame.width);
  const int height = std::max(codec.coded_height, frame.height);
  sws_.reset(sws_getCachedContext(sws_.release(), width, height, static_cast<AVPixelFormat>(frame.format), width,
                                  height, AV_PIX_FMT_BGR24, SWS_BICUBIC, nullptr, nullptr, nullptr));
  if (!sws_) throw std::runtime_error("swscale cannot convert this pixel format to BGR");
  if (frame.color_range == AVCOL_RANGE_JPEG) {
    int* inverse = nullptr;
    int* table = nullptr;
    int src_range = 0;
    int dst_range = 0;
    int brightness = 0;
    int contrast = 0;
    int saturation = 0;
    if (sws_getColorspaceDetails(sws_.get(), &inverse, &src_range, &table, &dst_range, &brightness, &contrast,
                                 &saturation) >= 0 &&
        src_range == 0) {
      sws_setColorspaceDetails(sws_.get(), inverse, 1, table, dst_range, brightness, contrast, saturation);
    }
  }
  if (!bgr_ || bgr_->width != width || bgr_->height != height) {
    bgr_.reset(av_frame_alloc());
    if (!bgr_) throw std::bad_alloc();
    bgr_->format = AV_PIX_FMT_BGR24;
    bgr_->width = width;
    bgr_->height = height;
    if (av_frame_get_buffer(bgr_.get(), 32) < 0) throw std::bad_alloc();
  }
  sws_scale(sws_.get(), frame.data, frame.linesize, 0, frame.height, bgr_->data, bgr_->linesize);
  return {frame.height, frame.width, CV_8UC3, bgr_->data[0], static_cast<size_t>(bgr_->linesize[0])};
}

}  // namespace neopipe::pipeline::io::libav
