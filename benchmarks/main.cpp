// The duet command line program: run, compare, stability, element, demo. It holds no physics.
#include <cstdio>

int main() {
  std::puts("duet: command line under construction");
  return 0;
}
