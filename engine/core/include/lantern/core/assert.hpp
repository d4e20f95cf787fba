// Programmer-error checks: the first of Lantern's three error tiers.
//
// LANTERN_ASSERT(cond, msg) aborts with the condition, message, file and line when `cond`
// is false. It is compiled in when LANTERN_ENABLE_ASSERTS is defined (the default in every
// build type, see the LANTERN_ASSERTS CMake option) so that test builds keep the contracts
// that death tests pin. Use it for misuse of an API (stale handles, double adds), never for
// bad input from files or the user: those return a lantern::Result with a message.
#pragma once

namespace lantern::detail {
[[noreturn]] void assert_fail(const char* expr, const char* msg, const char* file, int line);
}

#if defined(LANTERN_ENABLE_ASSERTS)
#define LANTERN_ASSERT(cond, msg)                                                              \
    do {                                                                                       \
        if (!(cond)) [[unlikely]]                                                              \
            ::lantern::detail::assert_fail(#cond, (msg), __FILE__, __LINE__);                  \
    } while (false)
#else
#define LANTERN_ASSERT(cond, msg)                                                              \
    do {                                                                                       \
        (void)sizeof(cond);                                                                    \
    } while (false)
#endif

// Always-on check for conditions that would corrupt memory if violated (cheap, cold).
#define LANTERN_VERIFY(cond, msg)                                                              \
    do {                                                                                       \
        if (!(cond)) [[unlikely]]                                                              \
            ::lantern::detail::assert_fail(#cond, (msg), __FILE__, __LINE__);                  \
    } while (false)
