#include "graspkit/model/dof.hpp"

namespace graspkit {

char dofTypeLetter(DofType type) {
  switch (type) {
    case DofType::Rigid:
      return 'r';
    case DofType::Breakaway:
      return 'b';
    case DofType::Compliant:
      return 'c';
  }
  return 'r';
}

}  // namespace graspkit
