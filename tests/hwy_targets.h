// Runs a test body once per Highway target that is compiled in and supported by this CPU, with dispatch forced
// to that target (hwy::SetSupportedTargetsForTest), and restores normal dispatch afterwards, also when a REQUIRE
// throws. `dispatched_name` reports the target a kernel family actually dispatched to, so a test fails if the
// forcing did not reach it.
#pragma once
#include <hwy/highway.h>  // HWY_TARGETS
#include <hwy/targets.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <string>

namespace torte::test {

template <class F>
void for_each_hwy_target(const char* (*dispatched_name)(), F&& f) {
  struct Restore {
    ~Restore() { hwy::SetSupportedTargetsForTest(0); }
  } restore;
  const int64_t targets = HWY_TARGETS & hwy::SupportedTargets();
  REQUIRE(targets != 0);
  for (int64_t rest = targets; rest != 0; rest &= rest - 1) {
    const int64_t target = rest & -rest;
    hwy::SetSupportedTargetsForTest(target);
    const std::string name = hwy::TargetName(target);
    INFO("target " << name);
    REQUIRE(std::string(dispatched_name()) == name);
    f(name);
  }
}

}  // namespace torte::test
