# A small painted bar chart of the scaled Jacobian histogram (20 bins over [-1, 1]), its
# bars in the colours of the Mesh quality view (palette.BANDS).
from PySide import QtCore, QtGui

from VoroHexGui import palette

BIN_WIDTH = 0.1
LOW = -1.0


def bin_colour(lower):
    """The quality view's colour of the values in the bin [lower, lower + 0.1)."""
    return QtGui.QColor.fromRgbF(*palette.band_colour(lower + 0.5 * BIN_WIDTH))


class HistogramWidget(QtGui.QWidget):
    def __init__(self, parent=None):
        super().__init__(parent)
        self.counts = []
        self.setObjectName("histogram")
        self.setMinimumHeight(130)

    def set_counts(self, counts):
        self.counts = [int(c) for c in counts]
        self.update()

    def sizeHint(self):
        return QtCore.QSize(320, 140)

    def y_labels(self):
        top = max(self.counts) if self.counts else 0
        return [str(top), "0"]

    def plot_rect(self):
        """The bars' frame: left of it room for the widest y label, below for the x labels."""
        fm = self.fontMetrics()
        left = max(fm.horizontalAdvance(t) for t in self.y_labels() + ["0"]) + 8
        return self.rect().adjusted(left, fm.height() // 2 + 2, -14, -(fm.height() + 4))

    def paintEvent(self, event):
        p = QtGui.QPainter(self)
        p.setRenderHint(QtGui.QPainter.Antialiasing, False)
        rect = self.plot_rect()
        fm = self.fontMetrics()
        p.fillRect(self.rect(), self.palette().base())
        p.setPen(self.palette().text().color())
        p.drawRect(rect)
        if not self.counts or max(self.counts) == 0:
            p.drawText(rect, QtCore.Qt.AlignCenter, "no mesh")
            return
        # Only the bins from the first non-empty one (or 0) to 1 are drawn, so the usual
        # all-positive mesh uses the whole width; inverted bins show when present.
        first = min([i for i, c in enumerate(self.counts) if c] + [len(self.counts) // 2])
        shown = self.counts[first:]
        top = max(shown)
        w = rect.width() / len(shown)
        for k, c in enumerate(shown):
            lower = LOW + (first + k) * BIN_WIDTH
            h = int(round(rect.height() * c / top))
            bar = QtCore.QRectF(rect.left() + k * w + 1, rect.bottom() - h, max(w - 2, 1), h)
            p.fillRect(bar, bin_colour(lower))
        p.setPen(self.palette().text().color())
        for k in range(0, len(shown) + 1, max(1, len(shown) // 5)):
            x = rect.left() + k * w
            p.drawText(QtCore.QRectF(x - 20, rect.bottom() + 2, 40, fm.height() + 2),
                       QtCore.Qt.AlignCenter, "{:.1f}".format(LOW + (first + k) * BIN_WIDTH))
        label_w = rect.left() - 4
        for text, y in ((str(top), rect.top()), ("0", rect.bottom())):
            p.drawText(QtCore.QRectF(0, y - fm.height() / 2, label_w, fm.height()),
                       QtCore.Qt.AlignRight | QtCore.Qt.AlignVCenter, text)
