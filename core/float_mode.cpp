#include "core/float_mode.h"

#if defined(__x86_64__) || defined(__i386__)
#include <pmmintrin.h>
#include <xmmintrin.h>
#define GONIO_X86 1
#endif

namespace gonio {

void use_result_float_mode() {
#ifdef GONIO_X86
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
#endif
}

ResultFloatMode::ResultFloatMode() {
#ifdef GONIO_X86
    saved_ = _mm_getcsr();
#endif
    use_result_float_mode();
}

ResultFloatMode::~ResultFloatMode() {
#ifdef GONIO_X86
    _mm_setcsr(saved_);
#endif
}

bool in_result_float_mode() {
#ifdef GONIO_X86
    return _MM_GET_FLUSH_ZERO_MODE() == _MM_FLUSH_ZERO_ON &&
           _MM_GET_DENORMALS_ZERO_MODE() == _MM_DENORMALS_ZERO_ON;
#else
    return true;
#endif
}

} // namespace gonio
