#include "progress_window.h"

#include <QChart>
#include <QChartView>
#include <QComboBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineSeries>
#include <QPainter>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QValueAxis>
#include <QVBoxLayout>

#include "store/patient_library.h"
#include "train/progress.h"

namespace palpation::ui {

namespace {

QString pct(double f) { return QStringLiteral("%1 %").arg(f * 100.0, 0, 'f', 0); }
QString pct(const std::optional<double>& f) { return f ? pct(*f) : QStringLiteral("-"); }

void set_row(QTableWidget* t, int row, const QStringList& cells) {
  for (int c = 0; c < cells.size(); ++c) {
    auto* item = new QTableWidgetItem(cells[c]);
    item->setFlags(Qt::ItemIsSelectable | Qt::ItemIsEnabled);
    t->setItem(row, c, item);
  }
}

QTableWidget* make_table(const QStringList& headers) {
  auto* t = new QTableWidget(0, int(headers.size()));
  t->setHorizontalHeaderLabels(headers);
  t->verticalHeader()->setVisible(false);
  t->setEditTriggers(QAbstractItemView::NoEditTriggers);
  t->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  return t;
}

// One plot over the sessions: a line per series, the sessions on x.
void fill_chart(QChartView* view, const QString& title, const QList<QPair<QString, const app::train::ProgressSeries::Series*>>& series,
                int sessions, double scale, const QString& unit) {
  auto* chart = new QChart;
  chart->setTitle(title);
  auto* x = new QValueAxis;
  x->setRange(1, std::max(2, sessions));
  x->setTickCount(std::min(std::max(2, sessions), 10));
  x->setLabelFormat(QStringLiteral("%d"));
  auto* y = new QValueAxis;
  y->setTitleText(unit);
  chart->addAxis(x, Qt::AlignBottom);
  chart->addAxis(y, Qt::AlignLeft);
  double top = 0;
  for (const auto& [name, s] : series) {
    auto* line = new QLineSeries;
    line->setName(name);
    line->setPointsVisible(true);
    for (std::size_t i = 0; i < s->value.size(); ++i) {
      line->append(s->session[i], s->value[i] * scale);
      top = std::max(top, s->value[i] * scale);
    }
    chart->addSeries(line);
    line->attachAxis(x);
    line->attachAxis(y);
  }
  y->setRange(0, top > 0 ? top * 1.1 : 1.0);
  y->applyNiceNumbers();
  chart->legend()->setVisible(series.size() > 1);
  QChart* old = view->chart();
  view->setChart(chart);
  delete old;
}

}  // namespace

ProgressWindow::ProgressWindow(app::store::PatientLibrary* library, QWidget* parent) : QWidget(parent), library_(library) {
  setObjectName(QStringLiteral("ProgressWindow"));
  setWindowTitle(tr("Trainee progress"));
  tabs_ = new QTabWidget;

  auto* trainee_tab = new QWidget;
  trainees_ = new QComboBox;
  trainees_->setObjectName(QStringLiteral("ProgressTrainee"));
  sessions_ = make_table({tr("Date"), tr("Case"), tr("Sensitivity"), tr("False positives"), tr("Light"), tr("Medium"), tr("Deep"),
                          tr("Deep over tumours"), tr("Exam time (s)"), tr("Passed")});
  sessions_->setObjectName(QStringLiteral("ProgressSessions"));
  auto* plots = new QWidget;
  auto* grid = new QGridLayout(plots);
  for (int i = 0; i < 4; ++i) {
    auto* v = new QChartView;
    v->setRenderHint(QPainter::Antialiasing);
    v->setMinimumSize(280, 200);
    charts_ << v;
    grid->addWidget(v, i / 2, i % 2);
  }
  auto* split = new QSplitter(Qt::Vertical);
  split->addWidget(sessions_);
  split->addWidget(plots);
  split->setStretchFactor(1, 2);
  auto* pick = new QHBoxLayout;
  pick->addWidget(new QLabel(tr("Trainee:")));
  pick->addWidget(trainees_, 1);
  auto* tl = new QVBoxLayout(trainee_tab);
  tl->addLayout(pick);
  tl->addWidget(split, 1);
  tabs_->addTab(trainee_tab, tr("Trainee"));

  class_ = make_table({tr("Trainee"), tr("Exams"), tr("Passed"), tr("Latest"), tr("Latest sensitivity"), tr("Latest false positives"),
                       tr("Latest deep coverage"), tr("Best"), tr("Best sensitivity"), tr("Best false positives"),
                       tr("Best deep coverage")});
  class_->setObjectName(QStringLiteral("ProgressClass"));
  tabs_->addTab(class_, tr("Class"));

  message_ = new QLabel;
  message_->setWordWrap(true);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(tabs_, 1);
  layout->addWidget(message_);
  connect(trainees_, &QComboBox::currentIndexChanged, this, [this] { show_trainee(); });
  resize(1000, 760);
  refresh();
}

QString ProgressWindow::trainee() const { return trainees_->currentText(); }

bool ProgressWindow::select_trainee(const QString& name) {
  const int i = trainees_->findText(name);
  if (i < 0) return false;
  trainees_->setCurrentIndex(i);
  show_trainee();
  return true;
}

void ProgressWindow::refresh() {
  message_->clear();
  const QString was = trainees_->currentText();
  {
    const QSignalBlocker block(trainees_);
    trainees_->clear();
    class_->setRowCount(0);
    if (!library_) {
      message_->setText(tr("No patient library is open: no trainees."));
    } else {
      try {
        for (const auto& t : library_->trainees()) trainees_->addItem(QString::fromStdString(t.name));
        const auto summary = library_->class_summary();
        class_->setRowCount(int(summary.size()));
        for (int r = 0; r < int(summary.size()); ++r) {
          const auto& s = summary[std::size_t(r)];
          auto brief = [](const std::optional<app::store::ExamResult>& e) {
            if (!e) return QStringList{QStringLiteral("-"), QStringLiteral("-"), QStringLiteral("-"), QStringLiteral("-")};
            return QStringList{QString::fromStdString(app::train::result_date(*e) + "  " + e->case_name), pct(e->sensitivity),
                               QString::number(e->false_positives), pct(e->coverage_deep)};
          };
          set_row(class_, r,
                  QStringList{QString::fromStdString(s.trainee.name), QString::number(s.exams), QString::number(s.passed)} + brief(s.latest) +
                      brief(s.best));
        }
      } catch (const std::exception& e) {
        message_->setText(QString::fromStdString(e.what()));
      }
    }
    const int i = trainees_->findText(was);
    trainees_->setCurrentIndex(i >= 0 ? i : 0);
  }
  show_trainee();
}

void ProgressWindow::show_trainee() {
  sessions_->setRowCount(0);
  std::vector<app::store::ExamResult> results;
  if (library_ && !trainees_->currentText().isEmpty()) {
    try {
      results = library_->results(trainees_->currentText().toStdString());
    } catch (const std::exception& e) {
      message_->setText(QString::fromStdString(e.what()));
    }
  }
  sessions_->setRowCount(int(results.size()));
  for (int r = 0; r < int(results.size()); ++r) {
    const auto& e = results[std::size_t(r)];
    set_row(sessions_, r,
            {QString::fromStdString(e.started).replace(QLatin1Char('T'), QLatin1Char(' ')).remove(QLatin1Char('Z')),
             QString::fromStdString(e.case_name), pct(e.sensitivity), QString::number(e.false_positives),
             pct(e.coverage_light), pct(e.coverage_medium), pct(e.coverage_deep), pct(e.deep_reached),
             QString::number(e.exam_time, 'f', 0), e.passed ? tr("yes") : tr("no")});
  }
  const auto s = app::train::progress_series(results);
  fill_chart(charts_[0], tr("Sensitivity"), {{tr("Sensitivity"), &s.sensitivity}}, s.sessions, 100.0, QStringLiteral("%"));
  fill_chart(charts_[1], tr("False positives"), {{tr("False positives"), &s.false_positives}}, s.sessions, 1.0, QString());
  fill_chart(charts_[2], tr("Coverage"),
             {{tr("Light"), &s.coverage[0]}, {tr("Medium"), &s.coverage[1]}, {tr("Deep"), &s.coverage[2]}}, s.sessions, 100.0,
             QStringLiteral("%"));
  fill_chart(charts_[3], tr("Exam time"), {{tr("Exam time"), &s.exam_time}}, s.sessions, 1.0, QStringLiteral("s"));
}

}  // namespace palpation::ui
