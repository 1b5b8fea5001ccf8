#include "batch/OptionEntries.h"

#include "batch/OptionValues.h"

namespace encore::batch::optiontable {

Entry flag(std::string name, std::string help, std::function<void(BatchOptions&, bool)> set) {
    Description d;
    d.name = std::move(name);
    d.form = OptionForm::Flag;
    d.help = std::move(help);
    d.apply = [set](BatchOptions& options, std::string_view value,
                    std::string_view shown) -> Result<void> {
        ENCORE_TRY_ASSIGN(const bool on, parseFlag(value, shown));
        set(options, on);
        return Result<void>{};
    };
    return {std::move(d)};
}

Entry wholeNumber(std::string name,
                  std::string valueName,
                  std::string defaultValue,
                  std::string help,
                  std::uint64_t min,
                  std::uint64_t max,
                  std::function<void(BatchOptions&, std::uint64_t)> set) {
    Description d;
    d.name = std::move(name);
    d.form = OptionForm::WholeNumber;
    d.valueName = std::move(valueName);
    d.defaultValue = std::move(defaultValue);
    d.help = std::move(help);
    d.apply = [set, min, max](BatchOptions& options, std::string_view value,
                              std::string_view shown) -> Result<void> {
        ENCORE_TRY_ASSIGN(const std::uint64_t number, parseWholeNumber(value, shown, min, max));
        set(options, number);
        return Result<void>{};
    };
    return {std::move(d)};
}

Entry number(std::string name,
             std::string valueName,
             std::string defaultValue,
             std::string help,
             float min,
             float max,
             std::function<void(BatchOptions&, float)> set) {
    Description d;
    d.name = std::move(name);
    d.form = OptionForm::Number;
    d.valueName = std::move(valueName);
    d.defaultValue = std::move(defaultValue);
    d.help = std::move(help);
    d.apply = [set, min, max](BatchOptions& options, std::string_view value,
                              std::string_view shown) -> Result<void> {
        ENCORE_TRY_ASSIGN(const float parsed, parseNumber(value, shown, min, max));
        set(options, parsed);
        return Result<void>{};
    };
    return {std::move(d)};
}

Entry range(std::string name,
            std::string valueName,
            std::string defaultValue,
            std::string help,
            std::function<void(BatchOptions&, ValueRange)> set) {
    Description d;
    d.name = std::move(name);
    d.form = OptionForm::Range;
    d.valueName = std::move(valueName);
    d.defaultValue = std::move(defaultValue);
    d.help = std::move(help);
    d.apply = [set](BatchOptions& options, std::string_view value,
                    std::string_view shown) -> Result<void> {
        ENCORE_TRY_ASSIGN(const ValueRange parsed, parseRange(value, shown));
        set(options, parsed);
        return Result<void>{};
    };
    return {std::move(d)};
}

Entry text(std::string name,
           OptionForm form,
           std::string valueName,
           std::string help,
           std::function<Result<void>(BatchOptions&, std::string_view, std::string_view)> apply) {
    Description d;
    d.name = std::move(name);
    d.form = form;
    d.valueName = std::move(valueName);
    d.help = std::move(help);
    d.apply = std::move(apply);
    return {std::move(d)};
}

}  // namespace encore::batch::optiontable
