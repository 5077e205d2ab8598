// Inspection of a Voronoi graph: JSON for people and scripts, VTP (VTK XML PolyData) for
// ParaView.
//
// JSON layout:
//   {"elements": [{"id": 0, "kind": "vertex"|"edge"|"face",
//                  "governors": ["Face3", "Edge5", ...], "point": [x, y, z],
//                  "radius": r, "verified": true, "f_s": true (faces only),
//                  "polyline": [[x, y, z], ...] (edges only), "incident": [ids]}, ...],
//    "counts": {"vertices": n, "edges": n, "faces": n, "f_s": n},
//    "stats": {"cells": n, "seconds": s, ...}, "status": "ok", "diagnostics": [...]}
// VTP: vertices as points (cells of type vertex), edges as polylines, faces as points at a
// point of the face; cell data "kind" (0 face, 1 edge, 2 vertex), "f_s", "id" and a string
// array "governors" ("Face1 Face2"), so ParaView can colour and label them.
#pragma once

#include <string>

#include "voronoi/voronoi_graph.h"

namespace vorohex::voronoi {

// The graph as JSON text (indented).
std::string voronoi_graph_json(const VoronoiResult& result);

// Writes JSON (`json_path`, required) and, if `vtp_path` is not empty, a VTP file.
// Returns false and fills `error` when a file cannot be written.
bool write_voronoi_graph(const VoronoiResult& result, const std::string& json_path,
                         const std::string& vtp_path, std::string* error);

}  // namespace vorohex::voronoi
