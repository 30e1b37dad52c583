#pragma once
// Progress display of a run. On a terminal: one line redrawn in place (carriage return) with a
// bar, percent, simulated time, steps, steps/s and ETA, at most ~5 times a second. Elsewhere (CI,
// pipes, log files): a plain line every 10 % of the simulated time or every 30 s of wall time.
// update() is called every step and costs a counter increment and a comparison when it does not
// print: the clock is read only every `stride` calls, the stride adapting so that reads are
// ~10-50 ms of wall time apart.

#include <functional>
#include <ostream>
#include <string>

namespace duet {

class Progress {
 public:
  /// Seconds from any fixed origin; tests inject a fake one.
  using Clock = std::function<double()>;

  Progress(double total_time, std::ostream& out, bool is_terminal);
  Progress(double total_time, std::ostream& out, bool is_terminal, Clock clock);

  /// Report that the simulation has reached `sim_time` (s) after `steps` steps.
  void update(double sim_time, long steps) {
    last_sim_time_ = sim_time;
    last_steps_ = steps;
    if (++calls_since_check_ < stride_ && sim_time < next_report_time_) return;
    check(sim_time, steps);
  }
  /// Final line: the last state and `status` ("completed", "failed: ..."). Idempotent.
  void finish(const std::string& status);

  /// Clock reads so far (to check that update() stays cheap).
  long clock_reads() const { return clock_reads_; }

 private:
  void check(double sim_time, long steps);
  double read_clock();
  std::string state_text(double sim_time, long steps, double wall) const;
  void draw_bar(double sim_time, long steps, double wall);
  void print_line(double sim_time, long steps, double wall);
  double percent(double sim_time) const;

  double total_time_;
  std::ostream& out_;
  bool is_terminal_;
  Clock clock_;
  double start_ = 0.0;

  // Cheap path: clock read every stride_ calls, or when the next 10 % mark is reached (plain
  // mode only; the mark is +infinity on a terminal).
  long stride_ = 1;
  long calls_since_check_ = 0;
  double next_report_time_;
  double last_check_wall_ = 0.0;
  long clock_reads_ = 0;

  double last_print_wall_ = 0.0;
  std::size_t last_line_length_ = 0;
  double last_sim_time_ = 0.0;
  double last_printed_sim_time_ = -1.0;  // plain mode: simulated time of the last line
  long last_steps_ = 0;
  bool finished_ = false;
};

}  // namespace duet
