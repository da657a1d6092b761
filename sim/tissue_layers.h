// Tissue layers: the breast as skin, subcutaneous fat and glandular tissue, bands at
// given depths below the skin, laid onto a model's elements as their tissue (before
// tumours). The mesh is not changed: an element gets the modulus of the layers its depth
// span covers, averaged over its volume, so any mesh (the built-in breasts, boxes,
// imported scans) takes the same layers and the cached meshes stay valid.
#pragma once

#include <string>
#include <vector>

#include "model.h"

namespace palpation::sim {

/// The built-in breasts' layers (subcutaneous fat, glandular tissue), with the sources of
/// their figures in resources/tissue_presets.json ("layers").
std::vector<TissueLayer> breast_layers();

/// Young's modulus at depth d (m) below the skin.
double layer_modulus(const std::vector<TissueLayer>& layers, double d);

/// Per node, the distance (m) from its rest position to the nearest skin triangle: the
/// boundary faces that are not all on the chest wall (fixed). Values above `max_depth`
/// come back as `max_depth` (the search only looks that far).
std::vector<double> skin_depths(const Model& m, double max_depth);

/// Gives every element its layers' tissue, with the model's Poisson's ratio, and sets
/// m.tissue_young: an element within one band takes its modulus; one that a band boundary
/// cuts takes the harmonic volume average (the depth is linear across an element,
/// interpolated from its nodes): the modulus of the bands in series, as a fingertip loads
/// them, across their thickness. Measured on a layered breast, it is also the closer of the
/// two averages to a mesh that resolves the bands (docs/simulation.md, "Tissue layers").
/// Returns the number of elements whose centroid lies in each layer.
std::vector<int> apply_layers(Model& m, const std::vector<TissueLayer>& layers);

/// Puts the skin on m as a membrane over its skin triangles (the boundary faces not all
/// on the chest wall) with the tissue's Poisson's ratio; a spec without thickness takes
/// it off. The skin adds its in-plane stiffness E t to the surface and no mass (1.5 mm of
/// skin weighs a few percent of the elements under it).
void apply_skin(Model& m, const SkinSpec& spec);

}  // namespace palpation::sim
