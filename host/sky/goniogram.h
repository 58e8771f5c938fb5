// goniogram.h — the sky as a luminance table over the upper hemisphere, and optionally the
// ground's glow below it (DESIGN.md §1 "Sky", §6).
//
// A goniogram g holds luminance (cd/m^2) at the nodes of a (theta, phi) grid -- theta the zenith
// angle from +y, phi the azimuth from north (-z) towards east (+x) -- and is bilinear in
// (theta, phi) inside each cell. The grid may be uneven. Either it covers the upper hemisphere
// (theta to pi/2) and is zero below the horizon, or it covers the whole sphere (theta to pi) with
// a step at the horizon: the node pi/2 appears twice, the first row the sky's horizon, the
// second the ground's (withGround: Radiance gensky's glowing lower hemisphere). The cell between
// the two pi/2 rows has zero width, so every integral over it is 0 and no sampler draws it.
// Invariants, checked by the constructor: theta nodes strictly increasing from exactly 0 to
// exactly pi/2 (the doubles M_PI / 2 and 2 * M_PI), then, for a whole sphere, pi/2 once more and
// strictly increasing to exactly M_PI; phi nodes from exactly 0 to exactly 2 pi;
// values finite and >= 0; the phi = 0 and phi = 2 pi columns equal and the theta = 0 (and
// theta = pi) row constant, because each is one set of directions -- so g is a continuous
// function on each hemisphere and the table cannot contradict itself.
//
// Emission (§3.1, §3.2) picks a cell by its integral of g sin(theta) and a direction inside it by
// the bilinear density, so the exact cell integrals live here, with F_ij = ∫_cell w g dw.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace fen {

class Goniogram {
public:
    // theta: node zenith angles (rad), strictly increasing, first exactly 0, last exactly pi/2;
    // or, for the whole sphere, continuing with pi/2 again and on to exactly pi (see above).
    // phi: node azimuths (rad), strictly increasing, first exactly 0, last exactly 2 pi.
    // values: luminance (cd/m^2) at the nodes, row-major: values[i * phi.size() + j] at
    // (theta[i], phi[j]). Any violation of the invariants above throws fen::Error, one line,
    // starting with `where`.
    Goniogram(std::vector<double> theta, std::vector<double> phi, std::vector<double> values,
              const std::string& where = "sky");

    std::size_t thetaCount() const { return theta_.size(); }  // node counts (cells: count - 1)
    std::size_t phiCount() const { return phi_.size(); }
    const std::vector<double>& theta() const { return theta_; }
    const std::vector<double>& phi() const { return phi_; }
    const std::vector<double>& values() const { return values_; }
    double value(std::size_t i, std::size_t j) const { return values_[i * phi_.size() + j]; }
    // Whether the table covers the lower hemisphere too (theta to pi), and its row at the nadir
    // (theta = pi; constant): the ground's luminance for a withGround() table, 0 without one.
    bool hasGround() const { return horizon_ + 1 < theta_.size(); }
    double groundLuminance() const { return hasGround() ? values_.back() : 0.0; }

    // Bilinear luminance (cd/m^2) at (theta, phi); phi is wrapped into [0, 2 pi); a negative theta
    // is the direction (-theta, phi + pi). theta <= pi/2 reads the sky's rows (the horizon itself
    // is sky); theta > pi/2 the ground's, or 0 without a ground. At a node it returns the node's
    // value exactly. NaN in, NaN out.
    double eval(double thetaRad, double phiRad) const;
    // The same towards a direction (any non-zero length); 0 below the horizon (y < 0) without a
    // ground.
    double evalDirection(const glm::dvec3& towardsSky) const;

    // Exact integrals over cell (i, j) = [theta_i, theta_i+1] x [phi_j, phi_j+1]
    // (i < thetaCount() - 1, j < phiCount() - 1, unchecked).
    double cellIntegralSin(std::size_t i,
                           std::size_t j) const;  // ∫∫ g sin(theta) dtheta dphi (cd/m^2 sr)
    double cellIntegralFlat(std::size_t i, std::size_t j) const;  // ∫∫ g dtheta dphi
    // F_ij = ∫_cell w g(w) dw (w the unit direction): the cell's share of the illuminance of any
    // plane that does not cut the cell is F_ij . n -- the three numbers per cell that the portal
    // strategy shares between all window triangles (DESIGN.md §3.2); illuminance() uses it too.
    glm::dvec3 cellDirectionIntegral(std::size_t i, std::size_t j) const;
    // ∫_cell g max(0, w . n) dw for a unit n: exact on a cell the plane does not cut (F_ij . n or
    // 0), converged like illuminance() on one it cuts. ∫_cell |w . n| g dw is this for n plus this
    // for -n: the portal strategy's eq. (2) per cell and portal plane.
    double cellClippedIntegral(std::size_t i, std::size_t j, const glm::dvec3& n) const;

    // ∫ over the table (the hemisphere, or the whole sphere with a ground) of g dw (cd/m^2 sr):
    // the sum of cellIntegralSin.
    double integral() const;
    // Illuminance (lux) of a plane with normal `normal` (any non-zero length) facing the sky:
    // ∫ g(w) max(0, w . n) dw, with relative error below 1e-6. Cells on one side of the plane
    // are exact (F_ij . n); the few that the plane cuts are split until the pieces are tiny.
    // With a ground, a plane facing down (n = -y) receives pi L_g, and one facing up only the sky.
    double illuminance(const glm::dvec3& normal) const;

    // The same function on a finer grid: each cell split evenly so that no theta step exceeds
    // maxThetaStepRad and no phi step exceeds maxPhiStepRad (to rounding; +infinity = no limit).
    // The new nodes take the bilinear values, so eval() agrees with this one to rounding.
    Goniogram refined(double maxThetaStepRad, double maxPhiStepRad) const;

    // This sky with the ground below the horizon glowing uniformly at `groundLuminance_cd_m2`
    // (finite, >= 0): the rows of this table, the horizon's row again with the ground's value,
    // and kGroundThetaSteps even ground rows down to the nadir (1 degree apart), on the same phi nodes.
    // Throws fen::Error (naming `where`) for a table that has a ground already or a bad value.
    static constexpr int kGroundThetaSteps = 90;  // 1 degree: sin(theta) varies little in a cell
    Goniogram withGround(double groundLuminance_cd_m2, const std::string& where = "sky") const;

private:
    std::vector<double> theta_, phi_, values_;
    std::size_t horizon_ = 0;  // the sky's horizon row (the first pi/2); the last row without a ground
};

// Unit vector towards the sky at (theta, phi): (sin theta sin phi, cos theta, -sin theta cos phi).
glm::dvec3 skyDirection(double thetaRad, double phiRad);
// Inverse of skyDirection for any non-zero vector: theta in [0, pi], phi in [0, 2 pi).
void skyAngles(const glm::dvec3& towardsSky, double* thetaRad, double* phiRad);

// A uniform sky of the given luminance (finite, >= 0; 0 is valid) on a grid of 90 theta steps
// of 1 degree and 4 phi cells, so that sampling a cell by its integral leaves little variation
// of sin(theta) inside it. Errors name `where` and the key: "<where>.luminance: ...".
Goniogram uniformSky(double luminance_cd_m2, const std::string& where = "sky");

// The user's table of DESIGN.md §6: zenith_deg strictly increasing from 0 to 90 and azimuth_deg
// strictly increasing from 0 to 360 (both ends given, steps may be uneven, azimuth from north
// towards east), luminance[i][j] (cd/m^2) at (zenith_deg[i], azimuth_deg[j]), finite and >= 0.
// The zenith row must be constant and the azimuth 0 and 360 columns equal (same directions).
// Every violation throws fen::Error naming `where` and the key, e.g.
// "scene.gltf: extras.sky.zenith_deg: must start at 0 and end at 90" or
// "scene.gltf: extras.sky.luminance[3][7]: negative luminance -2".
// The result is the table, bilinear, refined in theta to steps <= 1 degree (the same function).
Goniogram tableSky(const std::vector<double>& zenithDeg, const std::vector<double>& azimuthDeg,
                   const std::vector<std::vector<double>>& luminance, const std::string& where);

}  // namespace fen
