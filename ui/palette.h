#pragma once
// The colours the views and the widgets share, so a constraint's swatch in the list matches its vertices in 3D.
#include <QColor>

#include "core/fields/constraint_set.h"

namespace facehex::gui {

// A constraint's colour, from what it is, not where it stands in the list (deleting or adding one recolours no
// other): a side constraint by its side, an automatic feature by its feature, any other by its name.
QColor constraintColour(const Constraint& constraint);
// The colour of a field's gradient glyphs: u red, v green, w blue (the x, y, z convention of 3D axes).
QColor fieldColour(int field);
// The plane selection preview.
inline QColor selectionColour() { return QColor(255, 230, 0); }
// What a message named and the user asked to see: apart from every constraint colour and the selection.
inline QColor highlightColour() { return QColor(255, 0, 255); }
// The facial landmarks' markers: pure white stands out of the tinted constraint paint (the skin's is cyan).
inline QColor landmarkColour() { return QColor(255, 255, 255); }
// The model surface when no field is shown.
inline QColor tissueColour() { return QColor(235, 200, 175); }

}  // namespace facehex::gui
