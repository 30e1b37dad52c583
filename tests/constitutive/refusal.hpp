#pragma once
// Shared by the model tests: building a model from bad parameters must be refused with a message
// that contains every given fragment (the key, the value, the allowed range, the unit).

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "constitutive/registry.hpp"

namespace duet::constitutive {

inline void expect_model_refused(const std::string& model,
                                 std::map<std::string, ParameterValue> values,
                                 const std::string& context,
                                 const std::vector<std::string>& fragments) {
  try {
    make_model(model, std::move(values), context);
    ADD_FAILURE() << model << " accepted the parameters";
  } catch (const InputError& error) {
    const std::string message = error.what();
    for (const auto& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos) << message;
    }
  }
}

}  // namespace duet::constitutive
