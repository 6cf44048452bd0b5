/* rotor_fields.c: the double fields of the rotor model's input structs (autobal_rotor_hardware,
 * autobal_rotor_lumped) with their configuration sections, keys and SI units
 * (include/autobal/rotor.h): read by the CLI's config reader, the archive writers and the
 * sweeps/maps over any configuration key (autobal_rotor_stab_param_from_name). */
#include <stddef.h>

#include "autobal/rotor.h"

#define HW(sec, f, u) {sec, #f, u, offsetof(autobal_rotor_hardware, f), sec "." #f}
/* autobal_rotor_hardware: the masses and inertias in [rotor], the supports in [supports] */
static const autobal_rotor_field k_hw_fields[] = {
    HW("rotor", M_k, "kg"),         HW("rotor", A_k, "kg m^2"),     HW("rotor", m_p, "kg"),
    HW("rotor", A_p, "kg m^2"),     HW("rotor", C_p, "kg m^2"),     HW("supports", l_L, "m"),
    HW("supports", l_R, "m"),       HW("supports", c_Lx, "N/m"),    HW("supports", c_Ly, "N/m"),
    HW("supports", c_Lz, "N/m"),    HW("supports", c_Rx, "N/m"),    HW("supports", c_Ry, "N/m"),
    HW("supports", h_Lx, "N s/m"),  HW("supports", h_Ly, "N s/m"),  HW("supports", h_Lz, "N s/m"),
    HW("supports", h_Rx, "N s/m"),  HW("supports", h_Ry, "N s/m")};
#undef HW
#define LU(f, u) {"lumped", #f, u, offsetof(autobal_rotor_lumped, f), "lumped." #f}
static const autobal_rotor_field k_lumped_fields[] = {
    LU(M, "kg"),         LU(A, "kg m^2"),     LU(C, "kg m^2"),      LU(c_x, "N/m"),      LU(c_y, "N/m"),
    LU(c_z, "N/m"),      LU(c_alpha, "N m"),  LU(c_beta, "N m"),    LU(c_xbeta, "N"),    LU(c_yalpha, "N"),
    LU(h_x, "N s/m"),    LU(h_y, "N s/m"),    LU(h_z, "N s/m"),     LU(h_alpha, "N m s"), LU(h_beta, "N m s"),
    LU(h_xbeta, "N s"),  LU(h_yalpha, "N s")};
#undef LU
#define N_HW (sizeof k_hw_fields / sizeof k_hw_fields[0])
#define N_LUMPED (sizeof k_lumped_fields / sizeof k_lumped_fields[0])

const autobal_rotor_field *autobal_rotor_hardware_fields(size_t *n) {
  if (n) *n = N_HW;
  return k_hw_fields;
}
const autobal_rotor_field *autobal_rotor_lumped_fields(size_t *n) {
  if (n) *n = N_LUMPED;
  return k_lumped_fields;
}
double *autobal_rotor_field_ptr(void *base, const autobal_rotor_field *f) {
  return (double *)(void *)((char *)base + f->offset);
}
double autobal_rotor_field_get(const void *base, const autobal_rotor_field *f) {
  return *(const double *)(const void *)((const char *)base + f->offset);
}

