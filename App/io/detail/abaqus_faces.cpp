#include "io/detail/abaqus_faces.h"

namespace vorohex::io::detail {
int abaqus_face_number(int hex_face) {
  // kHexFaces: bottom {0,3,2,1} = S1, top {4,5,6,7} = S2, y0 {0,1,5,4} = S3,
  // y1 {2,3,7,6} = S5, x0 {0,4,7,3} = S6, x1 {1,2,6,5} = S4.
  static const int kNumber[6] = {1, 2, 3, 5, 6, 4};
  return kNumber[hex_face];
}

}  // namespace vorohex::io::detail
