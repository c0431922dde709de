// foglab — the reports' Russian text (core/language.h), in the lab manual's terms and
// symbols: смещение нуля (bias), масштабный коэффициент (scale factor), случайное блуждание
// угла (angle random walk), ρ the white noise's intensity, q the Wiener process's;
// е.м.р. (единица младшего разряда) the output's LSB, млн⁻¹ ppm.
#include "catalogue.h"

namespace foglab::detail {

namespace {

constexpr CatalogueEntry kEntries[] = {
    {Text::verbatim, "{}"},
    {Text::plots_skipped, "Графики не построены: {}."},
    {Text::plot_skipped, "График не построен: {}"},
    {Text::note, "Примечание: {}"},
    {Text::footer,
     "Отчёт построен программой foglab {}. Единицы: угловая скорость °/ч, время с, температура "
     "°C; параметры шума по IEEE Std 952 (ρ °/ч/√Гц, B °/ч, q °/ч/√с, R °/ч/с, Q °/ч·с)."},
    {Text::value, "значение"},
    {Text::interval95, "интервал 95 %"},
    {Text::unit, "единица"},
    {Text::cal_title, "Калибровка на поворотном стенде: {}"},
    {Text::cal_triad_title, "Калибровка триады на поворотном стенде: {}"},
    {Text::cal_section, "Калибровка"},
    {Text::cal_run,
     "Площадок: {}, значений температуры: {}, диапазон ±{} °/с, опорная температура T_0 = {} "
     "°C. Модель выходного сигнала (формула (10) пособия): u = S (1 + Σ s_k ΔT^k) [1 + Σ a_k "
     "ω^k + (A/2) sign ω] ω + u0 + Σ b_k ΔT^k, ΔT = T − T_0."},
    {Text::cal_coefficient, "коэффициент"},
    {Text::cal_row_s, "S, масштабный коэффициент при T_0"},
    {Text::cal_row_sk, "s_{}, его температурный коэффициент"},
    {Text::cal_row_ak, "a_{}, нелинейность на краю диапазона"},
    {Text::cal_row_a, "A, асимметрия масштабного коэффициента (S+ − S−)/S"},
    {Text::cal_row_u0, "u0, смещение нуля при T_0"},
    {Text::cal_row_u0_rate, "u0 в единицах угловой скорости"},
    {Text::cal_row_bk, "b_{}, температурный коэффициент смещения нуля"},
    {Text::unit_lsb_per_deg_s, "е.м.р./(°/с)"},
    {Text::unit_ppm_per_degc_k, "млн⁻¹/°C^{}"},
    {Text::unit_ppm_fs, "млн⁻¹ диапазона"},
    {Text::unit_ppm, "млн⁻¹"},
    {Text::unit_lsb, "е.м.р."},
    {Text::unit_deg_h, "°/ч"},
    {Text::unit_lsb_per_degc_k, "е.м.р./°C^{}"},
    {Text::cal_nonlinearity,
     "Нелинейность масштабного коэффициента: {} млн⁻¹ диапазона (по IEEE Std 952: наибольшее "
     "отклонение модели от её прямой), {} % (по лабораторной работе 1: разброс масштабных "
     "коэффициентов площадок); степень полинома f(ω): {}."},
    {Text::cal_noise,
     "Шум: ρ = {} °/ч/√Гц по отсчётам площадок (случайное блуждание угла {} °/√ч); остатки "
     "площадок {} е.м.р. (среднеквадратическое), степеней свободы: {}."},
    {Text::cal_weighting_noise,
     "Веса: ковариация средних по площадкам из модели шума остатков (ρ {} °/ч/√Гц, B {} °/ч, "
     "q {} °/ч/√с, экспоненциально-коррелированный процесс {} °/ч с временем корреляции {} с); "
     "хи-квадрат на степень свободы {}."},
    {Text::cal_weighting_alike,
     "Веса: все площадки одинаково (обычный метод наименьших квадратов)."},
    {Text::cal_budget, "Бюджет погрешности на краю диапазона (формула (13), 95 %):"},
    {Text::cal_budget_bias, "смещение нуля [°/ч]"},
    {Text::cal_budget_scale_factor, "масштабный коэффициент [°/ч]"},
    {Text::cal_budget_nonlinearity, "остаток нелинейности [°/ч]"},
    {Text::cal_budget_noise, "шум за 1 с [°/ч]"},
    {Text::cal_corrected_rate, "Измеренная угловая скорость (формула (11)):"},
    {Text::cal_equation,
     "ω [°/с] = (u − ({:.9g}{})) / ({:.10g} (1{}) (1{})),  ΔT = T − {:g} °C (ω в нелинейности: "
     "одна-две итерации)"},
    {Text::symbol_rate, "ω"},
    {Text::symbol_dt, "ΔT"},
    {Text::cal_plateaus, "Площадки"},
    {Text::cal_col_rate, "скорость [°/с]"},
    {Text::cal_col_samples, "отсчётов"},
    {Text::cal_col_mean, "средний выходной сигнал [е.м.р.]"},
    {Text::cal_col_sd, "СКО [е.м.р.]"},
    {Text::cal_col_temperature, "температура [°C]"},
    {Text::cal_col_residual, "остаток [е.м.р.]"},
    {Text::cal_fig_output,
     "Средний выходной сигнал площадок в зависимости от угловой скорости стенда и модель (10)"},
    {Text::cal_fig_scale_factor,
     "Масштабные коэффициенты площадок (u − u_0)/ω в зависимости от скорости и модель "
     "S(T) [1 + f(ω)]: нелинейность"},
    {Text::cal_fig_residual_rate, "Остатки площадок в зависимости от скорости"},
    {Text::cal_fig_residual_temperature, "Остатки площадок в зависимости от температуры"},
    {Text::cal_plot_output, "Выходной сигнал"},
    {Text::cal_plot_scale_factor, "Масштабный коэффициент"},
    {Text::cal_plot_residual_rate, "Остатки по скорости"},
    {Text::cal_plot_residual_temperature, "Остатки по температуре"},
    {Text::cal_axis_rate, "угловая скорость стенда [°/с]"},
    {Text::cal_axis_output, "выходной сигнал [е.м.р.]"},
    {Text::cal_axis_scale_factor, "масштабный коэффициент (u − u_0)/ω [е.м.р./(°/с)]"},
    {Text::cal_axis_residual, "остаток площадки [е.м.р.]"},
    {Text::cal_axis_temperature, "температура [°C]"},
    {Text::cal_legend_temperature, "{:.1f} °C"},
    {Text::cal_legend_plateaus, "площадки"},
    {Text::cal_misalignment, "Перекос осей"},
    {Text::cal_misalignment_text,
     "m_ij [мрад]: чувствительность гироскопа i к угловой скорости вокруг оси j, M = I + m "
     "(малые углы), с интервалами 95 %."},
    {Text::cal_gyro, "гироскоп"},
    {Text::cal_own_axis, "1 (масштабный коэффициент)"},
    {Text::cal_gyro_section, "Гироскоп {} ({})"},
    {Text::cal_gyro_plot, "гироскоп {}: {}"},
    {Text::cal_gyro_figure, "Гироскоп {}: {}"},
    // ---- lab 1's report ----
    // ---- lab 2's report ----
    // ---- analyze's report ----
    // ---- the analyses' notes ----
};

}  // namespace

std::span<const CatalogueEntry> catalogue_ru() { return kEntries; }

}  // namespace foglab::detail
