// The start of a bare-metal Cortex-M7 program under qemu-system-arm's mps2-an500 board
// (scripts/onboard_counts.sh): the vector table at address 0 (initial stack pointer, reset), and a
// reset that turns the FPU on before any floating-point instruction (CPACR: full access to CP10,
// CP11) and enters newlib's semihosting start-up (rdimon-crt0: .bss, constructors, main, exit).
#include <cstdint>

extern "C" [[noreturn]] void _start();
extern "C" [[noreturn]] void reset();

extern "C" void reset() {
  volatile std::uint32_t& cpacr = *reinterpret_cast<volatile std::uint32_t*>(0xE000ED88u);
  cpacr = cpacr | (0xFu << 20);
  asm volatile("dsb\n\tisb" ::: "memory");
  _start();
}

// The initial stack: the top of the board's second 4 MiB SSRAM (rdimon-crt0 sets its own from
// the semihosting heap information).
[[gnu::section(".vectors"), gnu::used]] const void* const vectors[2] = {reinterpret_cast<const void*>(0x20400000u),
                                                                     reinterpret_cast<const void*>(&reset)};
