// material_artist.h: the viewer's albedo / mean-free-path view of a material (materials/artist_parameters.h): the
// surface albedo and mfp a material's coefficients give under its model's inversion curve, and the coefficients
// from an edited albedo or mfp, by the same inversion `lucent materials invert` and the scene files use.
#pragma once
#include <optional>
#include <string>

#include "lucent/material.h"
#include "materials/artist_parameters.h"

namespace lucent::viewer {

// The albedo and mean free path [mm] of `m` (g, eta and model as they are); none when a band has no extinction
// (sigma_a + sigma_s = 0: an infinite mean free path) or no absorption (sigma_a = 0: albedo 1, outside the
// inversion's range).
std::optional<ArtistParameters> artist_parameters_of(const Material& m);

// Sets `m`'s sigma_a and sigma_s from `artist` (its g, eta and model are m's). Returns the error message and leaves
// `m` unchanged when the inversion refuses the values (an albedo the model cannot reach).
std::string apply_artist_parameters(Material& m, const ArtistParameters& artist);

}  // namespace lucent::viewer
