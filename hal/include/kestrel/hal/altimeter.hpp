#pragma once
// A height-above-floor sensor (sonar, or laser beams deflected down by a mirror).
#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel::hal {

class Altimeter {
 public:
  virtual Status poll(AltimeterSample& out) = 0;

 protected:
  ~Altimeter() = default;
};

}  // namespace kestrel::hal
