#include "common/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "common/timers.hpp"

namespace duet {

namespace {

constexpr double terminal_redraw_interval = 0.2;  // s of wall time: at most ~5 redraws a second
constexpr double plain_percent_step = 10.0;       // plain mode: a line every 10 % ...
constexpr double plain_wall_interval = 30.0;      // ... or every 30 s of wall time
constexpr double min_check_interval = 0.01;       // s between clock reads: stride doubles below
constexpr double max_check_interval = 0.05;       // ... and halves above
constexpr long max_stride = 4096;
constexpr int bar_width = 24;

std::string format(const char* fmt, double a) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, fmt, a);
  return buffer;
}

/// "42s", "3m 07s", "2h 05m".
std::string duration_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  const long s = std::lround(seconds);
  char buffer[48];
  if (s < 60) {
    std::snprintf(buffer, sizeof buffer, "%lds", s);
  } else if (s < 3600) {
    std::snprintf(buffer, sizeof buffer, "%ldm %02lds", s / 60, s % 60);
  } else {
    std::snprintf(buffer, sizeof buffer, "%ldh %02ldm", s / 3600, (s % 3600) / 60);
  }
  return buffer;
}

}  // namespace

Progress::Progress(double total_time, std::ostream& out, bool is_terminal)
    : Progress(total_time, out, is_terminal, steady_seconds) {}

Progress::Progress(double total_time, std::ostream& out, bool is_terminal, Clock clock)
    : total_time_(total_time),
      out_(out),
      is_terminal_(is_terminal),
      clock_(std::move(clock)),
      next_report_time_(is_terminal ? std::numeric_limits<double>::infinity()
                                    : total_time * plain_percent_step / 100.0) {
  start_ = read_clock();
  last_check_wall_ = start_;
  last_print_wall_ = start_;
}

double Progress::read_clock() {
  ++clock_reads_;
  return clock_();
}

double Progress::percent(double sim_time) const {
  if (!(total_time_ > 0.0)) return 100.0;
  return std::clamp(100.0 * sim_time / total_time_, 0.0, 100.0);
}

void Progress::check(double sim_time, long steps) {
  calls_since_check_ = 0;
  if (finished_) return;
  const double now = read_clock();
  // Adapt the stride so that clock reads stay between min and max_check_interval apart.
  const double since_check = now - last_check_wall_;
  last_check_wall_ = now;
  if (since_check < min_check_interval && stride_ < max_stride) {
    stride_ *= 2;
  } else if (since_check > max_check_interval && stride_ > 1) {
    stride_ /= 2;
  }

  const double wall = now - start_;
  if (is_terminal_) {
    if (now - last_print_wall_ >= terminal_redraw_interval) {
      draw_bar(sim_time, steps, wall);
      last_print_wall_ = now;
    }
    return;
  }
  const bool reached_mark = sim_time >= next_report_time_;
  if (reached_mark || now - last_print_wall_ >= plain_wall_interval) {
    print_line(sim_time, steps, wall);
    last_print_wall_ = now;
  }
  if (reached_mark && total_time_ > 0.0) {
    // Next multiple of 10 % strictly above the current percentage.
    const double mark =
        (std::floor(percent(sim_time) / plain_percent_step) + 1.0) * plain_percent_step;
    next_report_time_ =
        mark > 100.0 ? std::numeric_limits<double>::infinity() : total_time_ * mark / 100.0;
  } else if (reached_mark) {
    next_report_time_ = std::numeric_limits<double>::infinity();
  }
}

std::string Progress::state_text(double sim_time, long steps, double wall) const {
  std::string s = format("%5.1f%%", percent(sim_time));
  s += "  t = " + format("%.4g", sim_time) + " / " + format("%.4g", total_time_) + " s";
  s += "  steps " + std::to_string(steps);
  if (wall > 0.0) s += "  " + format("%.4g", static_cast<double>(steps) / wall) + " steps/s";
  // ETA from the average rate of simulated time per wall second since the start.
  const double rate = wall > 0.0 ? sim_time / wall : 0.0;
  const double eta =
      rate > 0.0 ? (total_time_ - sim_time) / rate : std::numeric_limits<double>::quiet_NaN();
  s += "  ETA " + duration_text(std::max(eta, 0.0));
  return s;
}

void Progress::draw_bar(double sim_time, long steps, double wall) {
  const int filled = static_cast<int>(percent(sim_time) / 100.0 * bar_width);
  std::string line = "[";
  line.append(static_cast<std::size_t>(filled), '#');
  line.append(static_cast<std::size_t>(bar_width - filled), '.');
  line += "] ";
  line += state_text(sim_time, steps, wall);
  const std::size_t length = line.size();
  // Pad over what is left of a longer previous line.
  if (length < last_line_length_) line.append(last_line_length_ - length, ' ');
  last_line_length_ = length;
  out_ << '\r' << line << std::flush;
}

void Progress::print_line(double sim_time, long steps, double wall) {
  out_ << "progress " << state_text(sim_time, steps, wall) << '\n' << std::flush;
  last_printed_sim_time_ = sim_time;
}

void Progress::finish(const std::string& status) {
  if (finished_) return;
  const double wall = read_clock() - start_;
  if (is_terminal_) {
    draw_bar(last_sim_time_, last_steps_, wall);
    out_ << '\n';
  } else if (last_sim_time_ != last_printed_sim_time_) {
    // Plain mode: the final state, unless the last line already shows it.
    print_line(last_sim_time_, last_steps_, wall);
  }
  finished_ = true;
  out_ << "finished after " << last_steps_ << " steps, " << duration_text(wall)
       << " of wall time: " << status << '\n'
       << std::flush;
}

}  // namespace duet
