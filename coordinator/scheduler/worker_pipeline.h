// How many units a worker should hold so that its threads never wait on the network. Each
// thread needs the unit it renders plus enough units on the way to cover the round trip
// (Little's law: units in flight = units per second × seconds in transit), plus a small
// prefetch. Units of cheap regions (background, diffuse walls) render several times faster
// than the mean, and a run of them would drain a pipeline sized for the mean: it covers twice
// the round trip. The round trip and a unit's render time are learnt from the worker's results;
// until the first result, the handshake's round trip and the time units are sized for
// (kUnitTargetSeconds) stand in for them, so a distant worker's pipeline is deep from its
// first units.
#pragma once

namespace tessera {

class WorkerPipeline {
 public:
  // `handshake_round_trip`: seconds from the coordinator's challenge to the worker's answer;
  // 0 when unknown.
  explicit WorkerPipeline(int threads, double handshake_round_trip = 0);

  // A result arrived `elapsed` seconds after its unit was sent; the worker reported `render`
  // seconds of rendering for it. The difference is the round trip plus any wait in the
  // worker's queue; its minimum is the round trip. Only a `full_sized` unit (about as many
  // pixels as the job's units are cut to) teaches the render time: a coarse level's unit of a
  // few pixels takes a fraction of a millisecond, and learning from it made a fresh worker's
  // pipeline deep enough to hold half a job (17 of the demo's 35 units on one of two workers,
  // which then finished them alone while the other idled: 80 ms of a 0.26 s job).
  void observe(double elapsed, double render, bool full_sized = true);

  int slots() const;
  double round_trip_seconds() const;  // 0 while unknown
  double unit_seconds() const { return unit_seconds_; }

 private:
  int threads_;
  double round_trip_ = -1;  // the smallest transit seen (the handshake's first); -1: none yet
  double unit_seconds_;     // moving average of render seconds per unit
  bool observed_ = false;   // whether unit_seconds_ has been measured, or is the target
};

}  // namespace tessera
