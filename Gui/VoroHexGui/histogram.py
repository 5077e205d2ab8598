# A small painted bar chart of the scaled Jacobian histogram (20 bins over [-1, 1]).
from PySide import QtCore, QtGui

BIN_WIDTH = 0.1
LOW = -1.0


def bin_colour(lower):
    """Red for inverted (< 0), orange for poor (< 0.2), amber below 0.5, green otherwise."""
    if lower < 0:
        return QtGui.QColor(200, 40, 40)
    if lower < 0.2:
        return QtGui.QColor(235, 130, 30)
    if lower < 0.5:
        return QtGui.QColor(220, 190, 40)
    return QtGui.QColor(60, 160, 80)


class HistogramWidget(QtGui.QWidget):
    def __init__(self, parent=None):
        super().__init__(parent)
        self.counts = []
        self.setMinimumHeight(130)

    def set_counts(self, counts):
        self.counts = [int(c) for c in counts]
        self.update()

    def sizeHint(self):
        return QtCore.QSize(320, 140)

    def paintEvent(self, event):
        p = QtGui.QPainter(self)
        p.setRenderHint(QtGui.QPainter.Antialiasing, False)
        rect = self.rect().adjusted(28, 6, -14, -20)
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
            p.drawText(QtCore.QRectF(x - 20, rect.bottom() + 2, 40, 16), QtCore.Qt.AlignCenter,
                       "{:.1f}".format(LOW + (first + k) * BIN_WIDTH))
        p.drawText(QtCore.QRectF(0, rect.top(), 26, 16), QtCore.Qt.AlignRight, str(top))
        p.drawText(QtCore.QRectF(0, rect.bottom() - 14, 26, 16), QtCore.Qt.AlignRight, "0")
