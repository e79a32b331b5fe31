#include "base/json_assert.h"

namespace crowdprof {

void json_assertion_failed(const char* condition) {
  throw JsonAssertion(std::string("a read the document does not support (nlohmann's check ") + condition + " failed)");
}

}  // namespace crowdprof
