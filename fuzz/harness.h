// The libFuzzer entry points every harness defines. Built with -fsanitize=fuzzer they are driven by libFuzzer;
// in the normal build replay_main.cc feeds them the seed corpus and the regression inputs.
#pragma once
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv);
