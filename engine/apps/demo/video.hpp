// Video output for tressvk-demo: RGBA frames piped to ffmpeg (from the system's PATH), encoded to a temporary
// file beside the output and renamed into place when ffmpeg succeeds, so a failed run leaves no partial video.
#pragma once

#include <tressvk/engine/image.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <sys/types.h>

namespace tressvk::demo {

// ffmpeg is not installed (or not on PATH). The message says how to install it.
class FfmpegMissing : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The path of the ffmpeg executable on PATH (or $TRESSVK_FFMPEG), or empty.
std::string find_ffmpeg();

class VideoWriter {
 public:
  // Starts ffmpeg. H.264 (yuv420p, even size) for .mp4/.mov/.mkv, ffmpeg's default for other extensions
  // (.gif works). Throws FfmpegMissing, or engine::Error when ffmpeg cannot be started.
  VideoWriter(const std::filesystem::path& path, uint32_t width, uint32_t height, double fps);
  ~VideoWriter();  // without finish(): stops ffmpeg and removes the temporary file
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  void write(const engine::Pixels& frame);  // 8-bit RGBA, the size given above
  void finish();                            // waits for ffmpeg; throws engine::Error when it failed

 private:
  void abort_encoder();
  std::filesystem::path path_, temp_;
  uint32_t width_, height_;
  int fd_ = -1;
  pid_t pid_ = -1;
};

}  // namespace tressvk::demo
