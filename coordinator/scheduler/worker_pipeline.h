// How many units a worker should hold so that its threads never wait on the network. Each
// thread needs the unit it renders plus enough units on the way to cover one round trip
// (Little's law: units in flight = units per second × seconds in transit), plus a small
// prefetch. The round trip and a unit's render time are learnt from the worker's results.
#pragma once

namespace tessera {

class WorkerPipeline {
 public:
  explicit WorkerPipeline(int threads) : threads_(threads) {}

  // A result arrived `elapsed` seconds after its unit was sent; the worker reported `render`
  // seconds of rendering for it. The difference is the round trip plus any wait in the
  // worker's queue; its minimum is the round trip.
  void observe(double elapsed, double render);

  int slots() const;
  double round_trip_seconds() const;  // 0 until a result arrived
  double unit_seconds() const { return unit_seconds_; }

 private:
  int threads_;
  double round_trip_ = -1;   // the smallest elapsed - render seen; -1: none yet
  double unit_seconds_ = 0;  // moving average of render seconds per unit
};

}  // namespace tessera
