#include "cli/batch_progress.h"

#include "cli/diagnosis_text.h"
#include "cli/text_format.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <sstream>

namespace xparam::cli {
namespace {

constexpr auto kRedrawEvery = std::chrono::milliseconds(500);
constexpr std::size_t kBarWidth = 20;

double seconds_between(std::chrono::steady_clock::time_point from, std::chrono::steady_clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

// Columns of the terminal on stderr (80 when unknown): live lines are cut to fit, since a
// wrapped line would throw off the cursor-up count.
std::size_t terminal_columns() {
  winsize size{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

std::string fitted(const std::string& line, std::size_t columns) {
  return line.size() < columns ? line : line.substr(0, columns - 1);
}

std::string bar(std::size_t done, std::size_t total) {
  const std::size_t filled = total == 0 ? kBarWidth : done * kBarWidth / total;
  return "[" + std::string(filled, '#') + std::string(kBarWidth - filled, '.') + "]";
}

}  // namespace

ProgressMode progress_mode_for_stderr(bool quiet) {
  if (quiet) return ProgressMode::Quiet;
  return isatty(STDERR_FILENO) == 1 ? ProgressMode::Live : ProgressMode::Plain;
}

std::string finished_line(const BatchProgress& progress) {
  const TargetOutcome& last = *progress.last;
  std::ostringstream line;
  line << "[" << progress.done << "/" << progress.total << "] ";
  if (!last.ok) {
    line << "FAILED " << last.name << ": " << last.error;
    return line.str();
  }
  const TargetMetrics& m = last.metrics;
  line << (last.suspect ? "suspect " : "ok ") << last.name << "  E_L2 " << figure(m.e_l2) << "  folds "
       << m.flipped_faces << " (strict " << m.strictly_folded_faces << ")  area " << figure(m.area_ratio);
  if (m.released_anchors > 0) line << "  released " << m.released_anchors;
  line << "  " << seconds_text(last.seconds);
  if (last.suspect) line << ": " << joined_reasons(last.diagnosis);
  return line.str();
}

BatchProgressView::BatchProgressView(ProgressMode mode, std::size_t total) : mode_(mode), total_(total) {
  last_.total = total;
  if (mode_ == ProgressMode::Live) ticker_ = std::thread([this] { ticker(); });
}

BatchProgressView::~BatchProgressView() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
  if (mode_ != ProgressMode::Live) return;
  // The running lines go; the overall line stays as the run's last word on the targets.
  erase_block_locked();
  if (total_ > 0) std::cerr << overall_line_locked() << "\n" << std::flush;
}

void BatchProgressView::preparing(const std::string& what) {
  const std::lock_guard lock(mutex_);
  preparing_ = what;
  if (mode_ == ProgressMode::Live) redraw_locked();
}

void BatchProgressView::stage(const std::string& target, const std::string& stage) {
  const std::lock_guard lock(mutex_);
  preparing_.clear();
  auto [it, added] = running_.try_emplace(target, Running{stage, Clock::now()});
  if (!added) it->second.stage = stage;
  if (mode_ == ProgressMode::Live) redraw_locked();
}

void BatchProgressView::finished(const BatchProgress& progress) {
  const std::lock_guard lock(mutex_);
  last_ = progress;
  running_.erase(progress.last->name);
  if (mode_ == ProgressMode::Quiet) return;
  if (mode_ == ProgressMode::Live) erase_block_locked();
  std::cerr << finished_line(progress) << "\n";
  if (mode_ == ProgressMode::Live) redraw_locked();
  std::cerr << std::flush;
}

std::string BatchProgressView::overall_line_locked() const {
  std::ostringstream line;
  const std::size_t ok = last_.done - last_.failed - last_.suspect;
  line << bar(last_.done, total_) << " " << last_.done << "/" << total_ << "  " << ok << " ok, " << last_.suspect
       << " suspect, " << last_.failed << " failed  " << seconds_text(seconds_between(start_, Clock::now()));
  // The rate and ETA from the finished targets (the first finished one starts them): targets
  // run side by side, so done / elapsed already counts the workers.
  if (last_.done > 0 && last_.elapsed_seconds > 0) {
    const double per_target = last_.elapsed_seconds / static_cast<double>(last_.done);
    line << "  " << seconds_text(per_target) << " per target, ETA "
         << seconds_text(per_target * static_cast<double>(total_ - last_.done));
  } else {
    line << "  ETA --";  // known once a target has finished
  }
  return line.str();
}

void BatchProgressView::erase_block_locked() {
  if (block_lines_ > 0) std::cerr << "\033[" << block_lines_ << "A";
  std::cerr << "\r\033[J";
  block_lines_ = 0;
}

void BatchProgressView::redraw_locked() {
  const std::size_t columns = terminal_columns();
  erase_block_locked();
  const Clock::time_point now = Clock::now();
  if (!preparing_.empty()) {
    std::cerr << fitted("  " + preparing_, columns) << "\n";
    ++block_lines_;
  }
  for (const auto& [name, running] : running_) {
    std::cerr << fitted("  " + name + "  " + running.stage + "  " + seconds_text(seconds_between(running.started, now)),
                        columns)
              << "\n";
    ++block_lines_;
  }
  if (total_ > 0) {
    std::cerr << fitted(overall_line_locked(), columns) << "\n";
    ++block_lines_;
  }
  std::cerr << std::flush;
}

void BatchProgressView::ticker() {
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, kRedrawEvery, [this] { return stopping_; })) redraw_locked();
}

}  // namespace xparam::cli
