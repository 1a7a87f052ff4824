#include "render/progress_bar.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "render/job_text.h"

namespace sph::ctl {

int terminal_width(int fd) {
  winsize ws{};
  if (ioctl(fd, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 20) return ws.ws_col;
  return 80;
}

void ProgressBar::update(const v1::ProgressInfo& p) {
  last_ = p;
  have_progress_ = true;
  draw(false);
}

void ProgressBar::message(const std::string& line) {
  std::fprintf(out_, "\r\x1b[K%s\n", line.c_str());
  drawn_ = false;
  if (have_progress_) draw(true);
  std::fflush(out_);
}

void ProgressBar::finish() {
  if (drawn_) std::fputc('\n', out_);
  drawn_ = false;
  std::fflush(out_);
}

void ProgressBar::draw(bool force) {
  const auto now = std::chrono::steady_clock::now();
  // At most ten redraws a second: a fast stream of events must not flood the terminal.
  if (!force && drawn_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  // A study's bar covers the whole ladder; the text names the level now running.
  const bool study = last_.has_study() && last_.study().levels() > 0;
  const double fraction = study ? std::clamp(last_.study().fraction(), 0.0, 1.0)
                          : last_.end_time() > 0
                              ? std::clamp(last_.time() / last_.end_time(), 0.0, 1.0)
                              : 0.0;
  char level[64] = "";
  if (study)
    std::snprintf(level, sizeof level, "  level %d/%d dx=%.3g", last_.study().level(),
                  last_.study().levels(), last_.study().dx());
  char tail[320];
  std::snprintf(tail, sizeof tail, " %5.1f%%%s  t=%.4g/%.4g s  step %lld  %s p-steps/s  ETA %s",
                100 * fraction, level, last_.time(), last_.end_time(),
                static_cast<long long>(last_.step()),
                format_count(last_.particle_steps_per_second()).c_str(),
                format_duration(study ? last_.study().eta_seconds() : last_.eta_seconds()).c_str());
  const std::string head = job_id_ + " ";
  const int width = terminal_width(fileno(out_));
  const int bar =
      std::max(10, width - static_cast<int>(head.size() + std::string(tail).size()) - 3);
  const int filled = static_cast<int>(std::lround(fraction * bar));
  std::string line = head + "[" + std::string(static_cast<size_t>(filled), '#') +
                     std::string(static_cast<size_t>(bar - filled), '.') + "]" + tail;
  if (static_cast<int>(line.size()) >= width) line.resize(static_cast<size_t>(width - 1));
  std::fprintf(out_, "\r\x1b[K%s", line.c_str());
  std::fflush(out_);
  drawn_ = true;
}

}  // namespace sph::ctl
