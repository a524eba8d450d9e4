// caoLineShading.h - how a line is lit without a normal (Benevides 2015, Sec. 2.1,
// the shading its comparisons use): the diffuse term averaged over the
// visible half of an infinitesimal cylinder (Mallo et al. 2005, Eq. 2.4-2.5)
// and the specular term of maximum reflection (Banks 1994, Eq. 2.3). The AO
// scales the ambient and the diffuse terms, as it does for surfaces.
#ifndef caoLineShading_h
#define caoLineShading_h

namespace cao
{

/// The cylinder-averaged diffuse term for unit tangent T, unit direction to
/// the light L and to the viewer V: sqrt(1 - L_T^2) (sin a + (pi - a) cos a)
/// / 4, a the angle between V and L projected on the plane normal to T
/// (Eq. 2.5); a headlight (L = V) across the line gives pi / 4. A zero
/// tangent (a point) is lit as a sphere facing the viewer: (1 + V.L) pi / 8.
double MalloDiffuse(const double T[3], const double L[3], const double V[3]);

/// MalloDiffuse relative to a line across a headlight (divided by pi / 4):
/// 1 there, so that a line lit that way keeps the colour it is drawn with
/// unlit (what the CLI's picture and the render pass scale by).
double MalloDiffuseRelative(const double T[3], const double L[3], const double V[3]);

/// Banks' specular term (-V_T L_T + sqrt(1 - V_T^2) sqrt(1 - L_T^2))^n,
/// clamped at 0.
double BanksSpecular(const double T[3], const double L[3], const double V[3], double exponent);

}

#endif
