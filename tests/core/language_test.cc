// core/language.h's Message: a catalogue sentence kept with its values and written in a
// language when shown (issue 20: the analyses' notes in Russian reports).
#include "foglab/core/language.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

namespace foglab {
namespace {

Message two_steps(Text kept_or_levelled) {
  std::vector<Message> steps;
  steps.emplace_back(Text::note_step_item, 12.5, 3600.0);
  steps.emplace_back(Text::note_step_item, -4.25, 7200.5);
  return Message(Text::note_steps, 2, std::move(steps), 6.0, kept_or_levelled);
}

TEST(Message, WritesItsSentenceWithItsValuesInEachLanguage) {
  const Message m = two_steps(Text::note_steps_kept);
  EXPECT_EQ(m.text(),
            "2 bias step(s): +12.5 deg/h at 3600 s, -4.25 deg/h at 7200.5 s (each beyond 6 robust "
            "spreads of the difference of the window means on either side); they were left in "
            "(not levelled)");
  EXPECT_EQ(m.text(Language::en), m.text());
  const std::string ru = m.text(Language::ru);
  // The numbers as in English, the words, the nested list and the chosen clause in Russian.
  EXPECT_NE(ru.find("+12.5 °/ч на 3600 с, -4.25 °/ч на 7200.5 с"), std::string::npos) << ru;
  EXPECT_NE(ru.find("скачков смещения нуля: 2"), std::string::npos) << ru;
  EXPECT_NE(ru.find("оставлены в записи"), std::string::npos) << ru;
  EXPECT_EQ(ru.find("deg/h"), std::string::npos) << ru;
}

TEST(Message, EmptyNestedAndVerbatimMessages) {
  const Message nothing;
  EXPECT_TRUE(nothing.empty());
  EXPECT_EQ(nothing.text(Language::ru), "");
  EXPECT_FALSE(Message(Text::note_no_white).empty());
  // An empty nested message says nothing where it stands.
  const Message flat(Text::temp_too_flat, 0.5, 2.0, Message());
  EXPECT_TRUE(flat.text().ends_with("the mean rate")) << flat.text();
  const Message asked(Text::temp_too_flat, 0.5, 2.0, Message(Text::temp_degree_asked, 2));
  EXPECT_TRUE(asked.text().ends_with("the mean rate (degree 2 was asked for)")) << asked.text();
  EXPECT_TRUE(asked.text(Language::ru).ends_with("(запрошена степень 2)"))
      << asked.text(Language::ru);
  // A sentence from outside the catalogue is the same in every language.
  const Message outside = Message::verbatim("matio: {not a placeholder}");
  EXPECT_EQ(outside.text(Language::ru), "matio: {not a placeholder}");
}

TEST(Message, AnInfiniteOrMissingNumberIsASymbolInRussian) {
  const Message m(Text::ev_none, std::numeric_limits<double>::infinity(),
                  Message(Text::ev_criteria, std::numeric_limits<double>::quiet_NaN(), 1.0, 2.0));
  EXPECT_NE(m.text().find("end slope inf"), std::string::npos) << m.text();
  const std::string ru = m.text(Language::ru);
  EXPECT_NE(ru.find("наклон в конце ∞"), std::string::npos) << ru;
  EXPECT_NE(ru.find("дрейфа —,"), std::string::npos) << ru;
  EXPECT_EQ(ru.find("inf"), std::string::npos) << ru;
  EXPECT_EQ(ru.find("nan"), std::string::npos) << ru;
}

TEST(Message, ComparesByContent) {
  EXPECT_EQ(two_steps(Text::note_steps_kept), two_steps(Text::note_steps_kept));
  EXPECT_NE(two_steps(Text::note_steps_kept), two_steps(Text::note_steps_levelled));
  EXPECT_NE(Message(Text::note_fit, Message(Text::fit_degenerate, 10)),
            Message(Text::note_fit, Message(Text::fit_degenerate, 11)));
  const std::vector<std::string> english_texts =
      english({Message(Text::word_start), Message(Text::word_end)});
  EXPECT_EQ(english_texts, (std::vector<std::string>{"start", "end"}));
}

}  // namespace
}  // namespace foglab
