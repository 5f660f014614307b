// The query form, built from soiqd's own table of `soiq query`'s options (GET /soiq/v1/info,
// "query_options"), so a new option appears here without editing the page. The form's arguments are
// the URL's (name=hippocampus&select=...), in the table's order: a query can be shared and reloaded.

// How an option is asked, from what the table says about it (no option is named here):
//   no placeholder               a flag: a checkbox, sent as name=true
//   placeholder "A|B|C" of words  a choice: a <select> with "any" first
//   placeholder with FEATURE     a feature: text completed from the catalogue (the <datalist>)
//   repeatable                   a list of inputs with "+" to add one and "×" to remove one
function kindOf(option) {
  if (!option.placeholder) return 'flag';
  const choices = option.placeholder.split('|');
  if (choices.length > 1 && choices.every((c) => /^[A-Za-z][A-Za-z0-9_-]*$/.test(c))) return 'choice';
  return 'text';
}

const takesFeature = (option) => /FEATURE/.test(option.placeholder);

// The input's placeholder: the table's default when it has one worth reading ("the server's cap"),
// else its value pattern without the shell quotes the CLI's help wears.
function placeholderOf(option) {
  const pattern = option.placeholder.replace(/^'(.*)'$/, '$1');
  if (option.default) return `${pattern} (default: ${option.default})`;
  return takesFeature(option) ? `${pattern}, e.g. ${exampleOf(option)}` : pattern;
}

function exampleOf(option) {
  return option.repeatable && /OP/.test(option.placeholder) ? 'voxel_volume_mm3>4000' : 'sphericity';
}

function element(tag, attributes = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes)) {
    if (v === false || v === undefined || v === null) continue;
    if (k === 'text') e.textContent = v;
    else e.setAttribute(k, v === true ? '' : v);
  }
  e.append(...children);
  return e;
}

export class QueryForm {
  constructor(form, info) {
    this.form = form;
    this.options = info.query_options;
    this.features = info.features;
    this.datalist = form.querySelector('#feature-names');
    for (const option of this.options) {
      const fieldset = form.querySelector(option.stage1 ? '#stage1' : '#stage2');
      fieldset.querySelector('.fields').append(this.#field(option));
      fieldset.hidden = false;
    }
    this.refreshFeatureNames();
    // The intensity features' completions name an image: follow the modality the user picks.
    form.addEventListener('change', (event) => {
      if (/modality$/.test(event.target.name || '')) this.refreshFeatureNames();
    });
  }

  #field(option) {
    const id = `opt-${option.name}`;
    const kind = kindOf(option);
    const wrapper = element('div', {
      class: `field field-${kind}${option.repeatable ? ' field-repeatable' : ''}${takesFeature(option) ? ' field-feature' : ''}`,
      'data-option': option.name,
    });
    const help = element('span', { class: 'help', id: `${id}-help`, text: option.help });
    if (kind === 'flag') {
      const box = element('input', { type: 'checkbox', id, name: option.name, 'aria-describedby': help.id });
      wrapper.append(element('label', { for: id, class: 'check' }, box, ` ${option.name}`), help);
      return wrapper;
    }
    wrapper.append(element('label', { for: id, text: option.name }));
    if (option.repeatable) {
      const list = element('div', { class: 'repeat-list' });
      wrapper.append(list, help);
      this.#addRepeat(list, option, id);
      const add = element('button', {
        type: 'button',
        class: 'add',
        'aria-label': `add another ${option.name}`,
        title: `add another ${option.name}`,
        text: '+',
      });
      add.addEventListener('click', () => this.#addRepeat(list, option, id).focus());
      wrapper.querySelector('label').after(add);
      return wrapper;
    }
    wrapper.append(this.#input(option, id, help.id), help);
    return wrapper;
  }

  // One input of a repeatable option; the first keeps the label's id, the others say which they are.
  #addRepeat(list, option, id) {
    const index = list.children.length;
    const row = element('div', { class: 'repeat-row' });
    const input = this.#input(option, index === 0 ? id : `${id}-${index}`, `${id}-help`);
    if (index > 0) input.setAttribute('aria-label', `${option.name} ${index + 1}`);
    const remove = element('button', {
      type: 'button',
      class: 'remove',
      'aria-label': `remove this ${option.name}`,
      title: `remove this ${option.name}`,
      text: '×',
    });
    remove.addEventListener('click', () => {
      // The last one is emptied rather than removed, so the option stays in the form.
      if (list.children.length > 1) row.remove();
      else input.value = '';
    });
    row.append(input, remove);
    list.append(row);
    return input;
  }

  #input(option, id, helpId) {
    if (kindOf(option) === 'choice') {
      const select = element('select', { id, name: option.name, title: option.help, 'aria-describedby': helpId });
      select.append(element('option', { value: '', text: option.default ? `default (${option.default})` : 'any' }));
      for (const c of option.placeholder.split('|')) select.append(element('option', { value: c, text: c }));
      return select;
    }
    return element('input', {
      type: 'text',
      id,
      name: option.name,
      placeholder: placeholderOf(option),
      autocomplete: 'off',
      spellcheck: 'false',
      inputmode: /^[NY]$/.test(option.placeholder) ? 'numeric' : false,
      list: takesFeature(option) ? this.datalist.id : false,
      title: option.help,
      'aria-describedby': helpId,
    });
  }

  // The completions of a feature input: every catalogue name; shape features also as their
  // asymmetry; intensity features (which need a region and an image) with the inside region and a
  // 3 mm shell of each modality in view (the form's modality fields, else the usual three).
  refreshFeatureNames() {
    const modalities = new Set();
    for (const input of this.form.querySelectorAll('[name$="modality"]'))
      if (input.value.trim()) modalities.add(input.value.trim().toUpperCase());
    if (modalities.size === 0) ['MR', 'CT', 'PT'].forEach((m) => modalities.add(m));
    const names = [];
    for (const f of this.features) {
      const described = `${f.summary}${f.unit ? ` [${f.unit}]` : ''}`;
      if (f.family === 'intensity') {
        for (const m of modalities)
          for (const region of ['inside', 'shell:3']) names.push([`${f.name}[${region},${m}]`, described]);
      } else {
        names.push([f.name, described]);
        names.push([`asym(${f.name})`, `asymmetry (L - R) / mean of ${f.name}`]);
      }
    }
    this.datalist.replaceChildren(...names.map(([value, label]) => element('option', { value, label })));
  }

  // The arguments the form says, in the table's order; empty fields are left out.
  args() {
    const args = new URLSearchParams();
    for (const option of this.options) {
      for (const input of this.form.querySelectorAll(`[name="${CSS.escape(option.name)}"]`)) {
        if (input.type === 'checkbox') {
          if (input.checked) args.append(option.name, 'true');
        } else if (input.value.trim()) {
          args.append(option.name, input.value.trim());
        }
      }
    }
    return args;
  }

  // Fills the form from a URL's arguments (a shared link, a reload, the back button). Returns the
  // names soiqd's table does not know, for the page to say rather than drop silently.
  fill(args) {
    this.clear();
    const unknown = [];
    for (const name of new Set(args.keys())) {
      const option = this.options.find((o) => o.name === name);
      if (!option) {
        unknown.push(name);
        continue;
      }
      const values = args.getAll(name);
      const wrapper = this.form.querySelector(`[data-option="${CSS.escape(name)}"]`);
      if (option.repeatable) {
        const list = wrapper.querySelector('.repeat-list');
        values.forEach((value, i) => {
          const input = i === 0 ? list.querySelector('input') : this.#addRepeat(list, option, `opt-${name}`);
          input.value = value;
        });
      } else if (kindOf(option) === 'flag') {
        wrapper.querySelector('input').checked = values[0] !== 'false';
      } else {
        const input = wrapper.querySelector('input, select');
        const value = values[values.length - 1];
        // A value a <select> does not list (lower case, say) is kept by adding it: soiqd judges it.
        if (input.tagName === 'SELECT' && ![...input.options].some((o) => o.value === value))
          input.append(element('option', { value, text: value }));
        input.value = value;
      }
    }
    this.refreshFeatureNames();
    return unknown;
  }

  clear() {
    for (const list of this.form.querySelectorAll('.repeat-list'))
      while (list.children.length > 1) list.lastElementChild.remove();
    for (const input of this.form.querySelectorAll('input, select')) {
      if (input.type === 'checkbox') input.checked = false;
      else if (input.closest('.fields')) input.value = '';
      input.removeAttribute('aria-invalid');
    }
  }

  // The input an error's field names: "select[1]" is the second select, "min-age" the min-age.
  inputFor(field) {
    const match = /^([a-z-]+)(?:\[(\d+)\])?/.exec(field || '');
    if (!match) return null;
    const inputs = this.form.querySelectorAll(`[name="${CSS.escape(match[1])}"]`);
    return inputs[Number(match[2] || 0)] || null;
  }

  markInvalid(field) {
    for (const input of this.form.querySelectorAll('[aria-invalid]')) input.removeAttribute('aria-invalid');
    const input = this.inputFor(field);
    if (input) input.setAttribute('aria-invalid', 'true');
    return input;
  }
}
