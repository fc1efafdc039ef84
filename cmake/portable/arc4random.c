/* Portable builds link libstdc++ statically. GCC 12's libstdc++.a (std::random_device) references arc4random,
 * which glibc only has from 2.36; this definition on top of getrandom(2) keeps the binaries at GLIBC_2.34 so they
 * run on older distributions (Ubuntu 22.04, RHEL 9). */
#include <stddef.h>
#include <stdint.h>
#include <sys/random.h>

uint32_t arc4random(void) {
  uint32_t value = 0;
  while (getrandom(&value, sizeof value, 0) != (ssize_t)sizeof value) {
  }
  return value;
}
