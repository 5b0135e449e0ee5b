#include "place/place_result.h"

namespace slide::place {

const char* methodName(PlaceMethod m) { return m == PlaceMethod::SlideGraph ? "slidegraph" : "slidematch"; }

}  // namespace slide::place
