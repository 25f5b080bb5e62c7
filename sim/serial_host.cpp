#include "serial_host.h"

#include <avr_uart.h>
#include <sim_avr.h>
#include <sim_cycle_timers.h>

namespace sim {

SerialHost::SerialHost(avr_t* avr, uint32_t baud)
    : avr_(avr), byte_cycles_(uint64_t(avr->frequency) * 10 / baud) {
  // No stdio echo and no usleep on every status poll (simavr 1.6 defaults).
  uint32_t flags = 0;
  avr_ioctl(avr, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
  flags &= ~(AVR_UART_FLAG_STDIO | AVR_UART_FLAG_POLL_SLEEP);
  avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT),
                          &SerialHost::on_output, this);
  input_irq_ = avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
}

void SerialHost::add_line(const std::string& line) {
  script_.push_back(line);
  if (!finished_) return;
  finished_ = wait_sent_ = false;  // the script goes on: send it now, then WAIT again
  send_next();
}

void SerialHost::send_raw(const std::string& bytes, uint8_t together) {
  const bool idle = raw_pos_ >= raw_.size();
  raw_ += bytes;
  raw_together_ = together ? together : 1;
  if (idle) avr_cycle_timer_register(avr_, byte_cycles_ * raw_together_, &SerialHost::on_raw_slot, this);
}

uint64_t SerialHost::on_raw_slot(avr_t*, uint64_t when, void* self) {
  auto* host = static_cast<SerialHost*>(self);
  if (host->raw_pos_ >= host->raw_.size()) return 0;
  if (host->last_byte_cycle_ && (!host->min_byte_interval_ || when - host->last_byte_cycle_ < host->min_byte_interval_))
    host->min_byte_interval_ = when - host->last_byte_cycle_;
  host->last_byte_cycle_ = when;
  for (uint8_t k = 0; k < host->raw_together_ && host->raw_pos_ < host->raw_.size(); ++k) {
    const char c = host->raw_[host->raw_pos_++];
    avr_raise_irq(host->input_irq_, uint8_t(c));
    if (host->relay_) host->relay_byte(c, when);
  }
  if (host->raw_pos_ < host->raw_.size()) return when + host->byte_cycles_ * host->raw_together_;
  host->raw_.clear();  // drained: the queue starts again from empty
  host->raw_pos_ = 0;
  return 0;
}

// A line ends at CR or LF; an empty one (the LF of a CRLF) is no line, as
// for the firmware (docs/protocol.md).
void SerialHost::relay_byte(char c, uint64_t cycle) {
  if (c != '\n' && c != '\r') {
    if (relay_line_.empty()) relay_line_cycle_ = cycle;
    relay_line_ += c;
    return;
  }
  if (relay_line_.empty()) return;
  ++lines_sent_;
  responses_.push_back({relay_line_, "", "", relay_line_cycle_, 0});
  relay_line_.clear();
}

size_t SerialHost::on_reset() {
  const size_t dropped = raw_.size() - raw_pos_;
  raw_.clear();
  raw_pos_ = 0;
  relay_line_.clear();
  partial_.clear();
  next_answer_ = responses_.size();
  last_byte_cycle_ = 0;  // a new session: the gap across the reset is no byte interval
  return dropped;
}

const std::string& SerialHost::banner() const {
  static const std::string none;
  return received_.empty() ? none : received_.front();
}

bool SerialHost::is_ok(const std::string& answer) { return answer == "ok" || answer.rfind("ok ", 0) == 0; }

size_t SerialHost::lines_ok() const {
  size_t n = 0;
  for (const Response& r : responses_) n += is_ok(r.answer);
  return n;
}

std::vector<std::string> SerialHost::errors() const {
  std::vector<std::string> out;
  for (const Response& r : responses_) {
    if (!r.answer.empty() && !is_ok(r.answer)) out.push_back(r.answer);  // unanswered lines are no errors
  }
  return out;
}

std::vector<std::string> SerialHost::reasons() const {
  std::vector<std::string> out;
  for (const Response& r : responses_) {
    if (!r.answer.empty() && !is_ok(r.answer)) out.push_back(r.reason);
  }
  return out;
}

std::vector<std::string> SerialHost::messages() const {
  std::vector<std::string> out;
  for (size_t i = banner_lines_; i < received_.size(); ++i) {
    const std::string& l = received_[i];
    if (!is_ok(l) && l.rfind("error:", 0) != 0) out.push_back(l);
  }
  return out;
}

// The answer a received line completes, with the refusal's reason: grbl's
// `ok` or `error:N` (its reason the `[MSG:...]` line just before it),
// Marlin's `ok` (a refusal when an `Error:` line came just before it, or
// before the `Resend:` line before it: the answer is then that line).
bool SerialHost::answer_of(std::string& answer, std::string& reason) const {
  const std::string& line = received_.back();
  const size_t n = received_.size();
  const auto before = [&](size_t k) -> const std::string& { return received_[n - 1 - k]; };
  reason.clear();
  if (marlin_) {
    if (!is_ok(line)) return false;
    answer = line;
    size_t k = 1;
    if (n > banner_lines_ + 1 && before(1).rfind("Resend:", 0) == 0) k = 2;
    if (n > banner_lines_ + k && before(k).rfind("Error:", 0) == 0) {
      answer = before(k);
      reason = answer.substr(6);
    }
    return true;
  }
  if (!is_ok(line) && line.rfind("error:", 0) != 0) return false;
  answer = line;
  const std::string& msg = n > banner_lines_ + 1 ? before(1) : line;
  if (!is_ok(line) && msg.rfind("[MSG:", 0) == 0 && msg.back() == ']') reason = msg.substr(5, msg.size() - 6);
  return true;
}

void SerialHost::on_output(avr_irq_t*, uint32_t value, void* self) {
  auto* host = static_cast<SerialHost*>(self);
  const char c = char(value);
  if (c == '\n') {
    std::string line;
    line.swap(host->partial_);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    host->on_line(line);
  } else {
    host->partial_ += c;
  }
}

void SerialHost::on_line(const std::string& line) {
  received_.push_back(line);
  received_cycles_.push_back(avr_->cycle);
  const bool banner = received_.size() <= banner_lines_;
  if (received_.size() == 1) {
    marlin_ = line == "start";
    // grbl's and Marlin's banners are two lines; the lathe's own front end
    // greets with one ("avrmotion ...").
    banner_lines_ = line.rfind("avrmotion ", 0) == 0 ? 1 : 2;
  }
  std::string answer, reason;
  const bool answered = !banner && answer_of(answer, reason);
  if (relay_) {
    if (answered && next_answer_ < responses_.size()) {
      responses_[next_answer_].answer = answer;
      responses_[next_answer_].reason = reason;
      responses_[next_answer_++].answer_cycle = avr_->cycle;
    }
    return;
  }
  if (banner) {
    if (received_.size() == banner_lines_) send_next();  // the whole banner: the firmware is ready
    return;
  }
  if (!answered || !awaiting_answer_) return;
  awaiting_answer_ = false;
  if (wait_sent_) {
    finished_ = true;
    return;
  }
  responses_.back().answer = answer;
  responses_.back().reason = reason;
  responses_.back().answer_cycle = avr_->cycle;
  // An image with both styles answers in the one `$200` chose from the
  // next line on (docs/protocol.md): the host follows it.
  const std::string& sent = responses_.back().line;
  if (is_ok(answer) && (sent == "$200=0" || sent == "$200=1")) marlin_ = sent.back() == '1';
  send_next();
}

void SerialHost::send_next() {
  if (script_.empty()) {
    if (wait_sent_) return;
    wait_sent_ = true;
    outgoing_ = wait_line_ + "\n";
  } else {
    const std::string line = script_.front();
    script_.pop_front();
    ++lines_sent_;
    responses_.push_back({line, "", "", avr_->cycle, 0});
    outgoing_ = line + "\n";
  }
  outgoing_pos_ = 0;
  awaiting_answer_ = true;
  avr_cycle_timer_register(avr_, byte_cycles_, &SerialHost::on_byte_slot, this);
}

uint64_t SerialHost::on_byte_slot(avr_t* avr, uint64_t when, void* self) {
  auto* host = static_cast<SerialHost*>(self);
  if (host->outgoing_pos_ >= host->outgoing_.size()) return 0;
  avr_raise_irq(host->input_irq_, uint8_t(host->outgoing_[host->outgoing_pos_++]));
  (void)avr;
  return host->outgoing_pos_ < host->outgoing_.size() ? when + host->byte_cycles_ : 0;
}

}  // namespace sim
