/**
 * caoOpacity.h — what every kind of AO reads of an opacity: its correction
 * for the length of the step that samples it (the volumes' LAO, and the
 * volumes occluding surfaces' cones).
 */
#ifndef caoOpacity_h
#define caoOpacity_h

namespace cao
{
/// Step-length correction of an opacity for samples `stepOverUnit` unit
/// distances apart: 1 - (1 - a)^(step/unit), computed in double, exact at 0 and 1.
float CorrectOpacity(double alpha, double stepOverUnit);
}

#endif
