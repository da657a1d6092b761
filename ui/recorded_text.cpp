#include "recorded_text.h"

#include <QRegularExpression>

namespace palpation::ui {

namespace {

QRegularExpressionMatch whole(const QString& pattern, const QString& s) {
  const QRegularExpression re(QRegularExpression::anchoredPattern(pattern));
  return re.match(s);
}

// The tumour editor's texts (ui/tumour_editor.cpp, undo-command names) as recorded by an
// English session: translated through TumourEditor's own catalogue entries.
QString editor_text(const QString& s) {
  auto ed = [](const char* source, int n = -1) { return QCoreApplication::translate("palpation::ui::TumourEditor", source, nullptr, n); };
  QRegularExpressionMatch m;
  if ((m = whole(QStringLiteral("Undo: (.*)"), s)).hasMatch()) return QCoreApplication::translate("QObject", "Undo: %1").arg(editor_text(m.captured(1)));
  if ((m = whole(QStringLiteral("Add tumour: (.*)"), s)).hasMatch()) return ed("Add tumour: %1").arg(editor_text(m.captured(1)));
  if ((m = whole(QStringLiteral("Remove tumour: (.*)"), s)).hasMatch()) return ed("Remove tumour: %1").arg(editor_text(m.captured(1)));
  if ((m = whole(QStringLiteral("(Paint|Erase) stroke \\((\\d+) elements?\\)"), s)).hasMatch()) {
    const int n = m.captured(2).toInt();
    return m.captured(1) == QLatin1String("Paint") ? ed("Paint stroke (%n elements)", n) : ed("Erase stroke (%n elements)", n);
  }
  if ((m = whole(QStringLiteral("(Sphere|Ellipsoid) at \\(([^,]+), ([^,]+), ([^)]+)\\) cm, ([^ ]+) kPa"), s)).hasMatch())
    return ed("%1 at (%2, %3, %4) cm, %5 kPa")
        .arg(ed(m.captured(1) == QLatin1String("Sphere") ? "Sphere" : "Ellipsoid"), m.captured(2), m.captured(3), m.captured(4),
             m.captured(5));
  if ((m = whole(QStringLiteral("Painted tumour (\\d+), ([^ ]+) kPa"), s)).hasMatch())
    return ed("Painted tumour %1, %2 kPa").arg(m.captured(1), m.captured(2));
  if (s == QLatin1String("Patient's tumour")) return ed("Patient's tumour");
  if (s == QLatin1String("Paint")) return ed("Paint");  // one dab of a stroke
  if (s == QLatin1String("Erase")) return ed("Erase");
  return s;
}

}  // namespace

QString RecordedText::event(const std::string& text) {
  const QString s = QString::fromStdString(text);
  // Fixed phrases (app/live/workstation.cpp, ui/main_window.cpp).
  if (s == QLatin1String("device: mouse palpation")) return tr("device: mouse palpation");
  if (s == QLatin1String("device: scripted hand")) return tr("device: scripted hand");
  if (s == QLatin1String("trainee mode")) return tr("trainee mode");
  if (s == QLatin1String("instructor mode")) return tr("instructor mode");
  if (s == QLatin1String("solver/contact parameters changed")) return tr("solver/contact parameters changed");
  QRegularExpressionMatch m;
  // A trainee's mark (app/review/review_session.cpp): "trainee mark N[ at (x, y, z) cm][: note]".
  if ((m = whole(QStringLiteral("trainee mark (\\d+)(?: at \\(([^,]+), ([^,]+), ([^)]+)\\) cm)?(?:: (.*))?"), s)).hasMatch()) {
    QString out = m.captured(2).isEmpty() ? tr("trainee mark %1").arg(m.captured(1))
                                          : tr("trainee mark %1 at (%2, %3, %4) cm")
                                                .arg(m.captured(1), m.captured(2), m.captured(3), m.captured(4));
    if (m.hasCaptured(5) && !m.captured(5).isEmpty()) out += tr(": %1").arg(m.captured(5));
    return out;
  }
  if ((m = whole(QStringLiteral("patient loaded: (\\d+) nodes, (\\d+) tetrahedra, backend (.*)"), s)).hasMatch())
    return tr("patient loaded: %1 nodes, %2 tetrahedra, backend %3").arg(m.captured(1), m.captured(2), m.captured(3));
  if ((m = whole(QStringLiteral("loading patient: (.*)"), s)).hasMatch()) return tr("loading patient: %1").arg(m.captured(1));
  if ((m = whole(QStringLiteral("patient not loaded: (.*)"), s)).hasMatch()) return tr("patient not loaded: %1").arg(m.captured(1));
  if ((m = whole(QStringLiteral("simulation stopped: (.*)"), s)).hasMatch()) return tr("simulation stopped: %1").arg(m.captured(1));
  if ((m = whole(QStringLiteral("backend error: (.*); continuing on the CPU from rest \\(forces held, then blended\\)"), s)).hasMatch())
    return tr("backend error: %1; continuing on the CPU from rest (forces held, then blended)").arg(m.captured(1));
  if ((m = whole(QStringLiteral("simulation diverged \\((.*)\\): body reset to rest \\(forces held, then blended\\)"), s)).hasMatch())
    return tr("simulation diverged (%1): body reset to rest (forces held, then blended)").arg(m.captured(1));
  if ((m = whole(QStringLiteral("change: (.*)"), s)).hasMatch()) return tr("change: %1").arg(m.captured(1));
  return editor_text(s);
}

QString RecordedText::patient_description(const std::string& text) {
  const QString s = QString::fromStdString(text);
  QRegularExpressionMatch m;
  // app/store/patient_library.cpp's built-in patients.
  if ((m = whole(QStringLiteral("Healthy breast, (small|medium|large|wide and flat|narrow and projecting) \\(([\\d,]+) mL\\)(, the "
                                "paper's size)?, no tumour"),
                 s))
          .hasMatch()) {
    const QString size = m.captured(1);
    const QString what = size == QLatin1String("small")    ? tr("small")
                         : size == QLatin1String("medium") ? tr("medium")
                         : size == QLatin1String("large")  ? tr("large")
                         : size == QLatin1String("wide and flat") ? tr("wide and flat")
                                                                  : tr("narrow and projecting");
    return m.captured(3).isEmpty() ? tr("Healthy breast, %1 (%2 mL), no tumour").arg(what, m.captured(2))
                                   : tr("Healthy breast, %1 (%2 mL), the paper's size, no tumour").arg(what, m.captured(2));
  }
  if (s == QLatin1String("The paper's case: medium breast, tumour 3 cm diameter, 107 kPa, 1.5 cm below the skin"))
    return tr("The paper's case: medium breast, tumour 3 cm diameter, 107 kPa, 1.5 cm below the skin");
  if ((m = whole(QStringLiteral("Medium breast, (soft|firm|hard) tumour ([\\d.]+) cm diameter \\((\\d+) kPa\\), centre ([\\d.]+) cm "
                                "below the skin"),
                 s))
          .hasMatch()) {
    const QString h = m.captured(1);
    const QString hard = h == QLatin1String("soft") ? tr("soft") : h == QLatin1String("firm") ? tr("firm") : tr("hard");
    return tr("Medium breast, %1 tumour %2 cm diameter (%3 kPa), centre %4 cm below the skin")
        .arg(hard, m.captured(2), m.captured(3), m.captured(4));
  }
  return s;  // imported scans and custom patients: the user's own words
}

}  // namespace palpation::ui
