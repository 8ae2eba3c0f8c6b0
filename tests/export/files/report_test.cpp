// The plan report (export/files/report.h): a slippage where nothing presses the fibre on the
// mandrel (k_n = 0) is written "unbounded" (JSON null), never as the figure 1e12.
#include "export/files/report.h"

#include <gtest/gtest.h>

#include "export/files/export_result.h"

namespace windplan {
namespace {

TEST(Report, UnboundedSlippageIsNotPrintedAsAMeasurement) {
  WindingPlan plan;
  plan.job_name = "t";
  plan.metrics.max_slippage = kUnboundedSlippage;
  plan.metrics.turnarounds.max_slippage = 0.125;
  const ExportResult result;
  const std::string md = report_markdown(plan, result);
  const std::string text = summary_text(plan, result);
  const std::string json = report_json(plan, result);
  for (const std::string* s : {&md, &text, &json}) {
    EXPECT_EQ(s->find("1e+12"), std::string::npos) << *s;
    EXPECT_EQ(s->find("1000000000000"), std::string::npos) << *s;
  }
  EXPECT_NE(md.find("| max slippage | unbounded"), std::string::npos) << md;
  EXPECT_NE(text.find("max slippage     unbounded"), std::string::npos) << text;
  EXPECT_NE(json.find("\"max_slippage\": null"), std::string::npos) << json;
  EXPECT_NE(md.find("| turnaround max slippage | 0.1250"), std::string::npos) << md;
  EXPECT_TRUE(is_unbounded_slippage(kUnboundedSlippage));
  EXPECT_FALSE(is_unbounded_slippage(3.5));
}

}  // namespace
}  // namespace windplan
