#pragma once
// The colours the views and the widgets share, so a constraint's swatch in the list matches its vertices in 3D.
#include <QColor>

namespace facehex::gui {

// A distinct colour per constraint (index into the list), cycling through a qualitative palette.
QColor constraintColour(int index);
// The colour of a field's gradient glyphs: u red, v green, w blue (the x, y, z convention of 3D axes).
QColor fieldColour(int field);
// The plane selection preview.
inline QColor selectionColour() { return QColor(255, 230, 0); }
// The model surface when no field is shown.
inline QColor tissueColour() { return QColor(235, 200, 175); }

}  // namespace facehex::gui
