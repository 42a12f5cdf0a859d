// constants.h: mathematical constants shared by C++ and GLSL.
#ifndef LUCENT_BSSRDF_CONSTANTS_H
#define LUCENT_BSSRDF_CONSTANTS_H
#include "shared/bridge.h"

LUCENT_SHADER_BEGIN
LUCENT_CONST float kPi = 3.14159265358979f;
LUCENT_CONST float kTwoPi = 6.28318530717959f;
LUCENT_CONST float kInvPi = 0.318309886183791f;
LUCENT_CONST float kInvFourPiSquared = 0.0253302959105844f;  // 1 / (4 pi^2)
LUCENT_SHADER_END

#endif
