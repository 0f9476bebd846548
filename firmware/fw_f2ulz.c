/* float -> uint64_t without double. The M4F's FPU converts to 32-bit integers only, so the
 * compiler calls the run-time ABI's __aeabi_f2ulz for a float converted to a 64-bit
 * integer (the DBC's generated encoders do so for every unsigned signal: cantools'
 * cantools_unsigned_from_double); libgcc's goes through double (software, hundreds of
 * cycles). This one works on the float's bits: exact, a few instructions. The linker takes
 * it instead of libgcc's (an archive member is pulled only for a symbol still undefined). */
#include <stdint.h>
#include <string.h>

/* the run-time ABI's helpers take their arguments in core registers (base PCS), also in a
 * hard-float build */
__attribute__((pcs("aapcs"))) unsigned long long __aeabi_f2ulz(float f);

__attribute__((pcs("aapcs"))) unsigned long long __aeabi_f2ulz(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    int exp = (int)((u >> 23) & 0xFFu) - 127;
    if ((u >> 31) || exp < 0) /* negative (C leaves it undefined) or below 1: 0 */
        return 0u;
    if (exp >= 64) /* too large, infinite or NaN: saturated */
        return UINT64_MAX;
    uint64_t mant = (u & 0x7FFFFFu) | 0x800000u; /* the value is mant x 2^(exp - 23) */
    return exp >= 23 ? mant << (exp - 23) : mant >> (23 - exp);
}
