#include "softsim/haptic/view_pointer.hpp"

#include <cmath>

namespace softsim::haptic {

PointerTrack::PointerTrack(const Eigen::Vector3d& start, double latency, double resync)
    : latency_(latency), resync_(resync) {
  current_.position = start;
}

void PointerTrack::append(const PointerSample& s) {
  if (count_ == kCapacity) {
    first_ = (first_ + 1) % kCapacity;
    --count_;
  }
  ring_[(first_ + count_) % kCapacity] = s;
  ++count_;
}

void PointerTrack::push(const PointerSample& s, double now) {
  if (anchored_ && !(s.t > last_sent_)) return;  // not after the last one: ignored (the transport refuses it)
  last_sent_ = s.t;
  PointerSample mapped = s;
  mapped.t = s.t + offset_;
  // A first sample, or one far from where the mapping expects it: the sender's clock is mapped
  // so that this sample plays `latency` from now, and the tip moves there from where it is.
  if (!anchored_ || std::abs(mapped.t - (now + latency_)) > resync_) {
    offset_ = now + latency_ - s.t;
    mapped.t = now + latency_;
    count_ = 0;
    PointerSample from = current_;
    from.t = now;
    append(from);
    anchored_ = true;
  }
  append(mapped);
}

const PointerSample& PointerTrack::at(double now) {
  if (count_ == 0) return current_;
  // Samples before the segment holding `now` are no longer needed.
  while (count_ >= 2 && sample(1).t <= now) {
    first_ = (first_ + 1) % kCapacity;
    --count_;
  }
  const PointerSample& a = sample(0);
  if (count_ == 1 || now <= a.t) {
    current_ = a;
  } else {
    const PointerSample& b = sample(1);
    const double s = (now - a.t) / (b.t - a.t);
    current_.position = (1 - s) * a.position + s * b.position;
    current_.blade = a.blade;
    current_.edge = a.edge;
  }
  current_.t = now;
  return current_;
}

}  // namespace softsim::haptic
