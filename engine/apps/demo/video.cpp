#include "video.hpp"

#include <tressvk/engine/check.hpp>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace tressvk::demo {

std::string find_ffmpeg() {
  if (const char* exe = std::getenv("TRESSVK_FFMPEG"); exe && *exe) return ::access(exe, X_OK) == 0 ? exe : "";
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  size_t b = 0;
  while (b <= dirs.size()) {
    const size_t e = std::min(dirs.find(':', b), dirs.size());
    const std::string dir = dirs.substr(b, e - b);
    const std::string exe = (dir.empty() ? std::string(".") : dir) + "/ffmpeg";
    struct stat st {};
    if (::stat(exe.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(exe.c_str(), X_OK) == 0) return exe;
    b = e + 1;
  }
  return "";
}

VideoWriter::VideoWriter(const std::filesystem::path& path, uint32_t width, uint32_t height, double fps)
    : path_(path), width_(width), height_(height) {
  const std::string ffmpeg = find_ffmpeg();
  if (ffmpeg.empty())
    throw FfmpegMissing("--video needs ffmpeg, which is not on PATH: install it (Debian: apt-get install ffmpeg, "
                        "or ./scripts/setup-deps.sh), or write PNG frames without --video");
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  // The temporary keeps the extension, which is how ffmpeg picks the container.
  temp_ = path.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + path.filename().string());
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool h264 = ext == ".mp4" || ext == ".mov" || ext == ".mkv" || ext == ".m4v";
  char size[32], rate[32];
  std::snprintf(size, sizeof size, "%ux%u", width, height);
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  std::vector<std::string> args = {ffmpeg, "-hide_banner", "-loglevel", "error", "-y", "-f", "rawvideo",
                                   "-pix_fmt", "rgba", "-s", size, "-r", rate, "-i", "pipe:0"};
  if (h264) {
    for (const char* a : {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-preset", "medium", "-crf",
                          "20", "-pix_fmt", "yuv420p", "-movflags", "+faststart"})
      args.emplace_back(a);
  }
  args.push_back(temp_.string());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  int fds[2];
  if (::pipe(fds) != 0) throw engine::Error(std::string("cannot create a pipe for ffmpeg: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], 0);
  posix_spawn_file_actions_addclose(&actions, fds[1]);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  const int rc = ::posix_spawn(&pid_, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[0]);
  if (rc != 0) {
    ::close(fds[1]);
    throw engine::Error("cannot start " + ffmpeg + ": " + std::strerror(rc));
  }
  fd_ = fds[1];
  std::signal(SIGPIPE, SIG_IGN);  // ffmpeg exiting early is an error we report, not a signal that kills us
}

VideoWriter::~VideoWriter() {
  if (pid_ > 0) abort_encoder();
}

void VideoWriter::abort_encoder() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (pid_ > 0) {
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
  pid_ = -1;
  std::error_code ec;
  std::filesystem::remove(temp_, ec);
}

void VideoWriter::write(const engine::Pixels& frame) {
  if (frame.width != width_ || frame.height != height_ || frame.texel_size != 4)
    throw engine::Error("video frame of the wrong size or format");
  const uint8_t* p = frame.data.data();
  size_t left = frame.data.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = std::strerror(errno);
      abort_encoder();
      throw engine::Error("ffmpeg stopped reading frames (" + why + ") while writing " + path_.string() +
                          "; its messages are above");
    }
    p += n;
    left -= static_cast<size_t>(n);
  }
}

void VideoWriter::finish() {
  ::close(fd_);
  fd_ = -1;
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
    throw engine::Error("ffmpeg failed to encode " + path_.string() + " (exit status " +
                        std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + "); its messages are above");
  }
  std::error_code ec;
  std::filesystem::rename(temp_, path_, ec);
  if (ec) {
    std::filesystem::remove(temp_, ec);
    throw engine::Error(path_.string() + ": cannot move the encoded video into place");
  }
}

}  // namespace tressvk::demo
