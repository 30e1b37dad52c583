#include "benchmarks/thread_choice.hpp"

#include <omp.h>

#include <cstdlib>
#include <string>

namespace duet {
namespace {

Json environment_value(const char* name) {
  const char* value = std::getenv(name);
  return value ? Json(std::string(value)) : Json();
}

}  // namespace

Json thread_choice() {
  Json j = Json::object();
  j["count"] = static_cast<long>(omp_get_max_threads());
  j["OMP_WAIT_POLICY"] = environment_value("OMP_WAIT_POLICY");
  j["GOMP_SPINCOUNT"] = environment_value("GOMP_SPINCOUNT");
  const char* choice = std::getenv("DUET_THREADS_CHOICE");
  j["chosen_by"] = std::string(choice ? choice : "the caller's environment");
  return j;
}

}  // namespace duet
